// The reference scenes' world-space triangles: the SAH build is well formed and no worse than
// a median split, and traversal agrees with brute force. Prints the costs and build times the
// device builder will be compared with.
#include <chrono>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "bvh/reference_builder.h"
#include "scenes/reference_scenes.h"
#include "tests/bvh/bvh_test_support.h"

namespace hmb::bvh::test {
namespace {

class ReferenceSceneBvh : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceSceneBvh, SahBuildIsSoundAndTracesLikeBruteForce) {
  const scene::Scene scene = scene::makeReferenceScene(GetParam());
  const TriangleMesh mesh = sceneTriangles(scene, scene.settings.frameTime);
  const PrimitiveBounds input = triangleBounds(mesh.view());
  const auto start = std::chrono::steady_clock::now();
  const Bvh sah = buildReferenceSah(input.bounds, input.centroids);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const Bvh median = buildMedianSplit(input.bounds, input.centroids, 4);
  ASSERT_EQ(structuralProblem(sah, input.bounds, 4), "");
  const double sahValue = sahCost(sah), medianValue = sahCost(median);
  std::printf("[ scene    ] %-12s %6u triangles: build %.3f s, depth %u, SAH full sweep %.3f, median split %.3f "
              "(%.3fx)\n",
              GetParam().c_str(), mesh.triangleCount(), seconds, depthOf(sah), sahValue, medianValue,
              medianValue / sahValue);
  EXPECT_LE(sahValue, medianValue);
  const Agreement agreement = compareWithBruteForce(sah, mesh.view(), mixedRays(mesh, 1000, 81));
  EXPECT_EQ(agreement.mismatches, 0u) << agreement.firstMismatch;
  EXPECT_GE(agreement.hits, 400u);
}

INSTANTIATE_TEST_SUITE_P(ReferenceScenes, ReferenceSceneBvh, ::testing::Values("living-room", "temple", "bistro"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

}  // namespace
}  // namespace hmb::bvh::test
