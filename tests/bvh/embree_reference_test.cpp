// Embree as the benchmark's CPU anchor answers the same queries as our brute force, and the tree
// its rtcBuildBVH makes converts into a well-formed BVH of SAH quality close to our reference
// builder's. Skipped when built without Embree.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include <gtest/gtest.h>

#include "bench/embree_reference.h"
#include "bvh/reference_builder.h"
#include "bvh/reference_traversal.h"
#include "tests/bvh/bvh_test_support.h"

namespace hmb::bvh::test {
namespace {

bool nearlyEqual(float a, float b, float relative) {
  return std::abs(a - b) <= relative * std::max({std::abs(a), std::abs(b), 1.0f});
}

struct EmbreeAgreement {
  uint32_t hits = 0;       // rays brute force saw hit something
  uint32_t tolerated = 0;  // another triangle, or far-off u and v, at the same t
  uint32_t mismatches = 0;
  std::string firstMismatch;
};

// Embree's triangle test rounds differently from our watertight one: t agrees to a few ulps,
// but u and v differ by up to about 1e-4 on small triangles, and far more on grazing rays. So a
// hit agrees when it is the same triangle at t within 1e-4 relative and u, v within 1e-3;
// another triangle at the same t (a tie or a shared edge), or the same one with u, v further
// off (a grazing ray), is tolerated but counted; anything else is a mismatch.
EmbreeAgreement compareWithEmbree(const TriangleList& triangles, std::span<const Ray> rays,
                                  std::span<const Hit> embreeHits) {
  EmbreeAgreement result;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit expected = bruteForceClosestHit(triangles, rays[i]);
    const Hit& actual = embreeHits[i];
    if (expected.triangle != HMB_NO_HIT) ++result.hits;
    if (expected.triangle == HMB_NO_HIT && actual.triangle == HMB_NO_HIT) continue;
    const bool bothHit = expected.triangle != HMB_NO_HIT && actual.triangle != HMB_NO_HIT;
    if (bothHit && nearlyEqual(expected.t, actual.t, 1e-4f)) {
      const bool agree = expected.triangle == actual.triangle && expected.objectId == actual.objectId &&
                         std::abs(expected.u - actual.u) <= 1e-3f && std::abs(expected.v - actual.v) <= 1e-3f;
      if (!agree) ++result.tolerated;
      continue;
    }
    if (result.mismatches++ == 0) {
      std::ostringstream s;
      s << "ray " << i << ": brute force triangle " << expected.triangle << " t " << expected.t << ", Embree triangle "
        << actual.triangle << " t " << actual.t;
      result.firstMismatch = s.str();
    }
  }
  return result;
}

TEST(EmbreeReference, HitsAgreeWithBruteForce) {
  if (!bench::embreeAvailable()) GTEST_SKIP() << "built without Embree";
  EXPECT_FALSE(bench::embreeVersion().empty());
  for (uint32_t seed : {1u, 2u})
    for (float size : {0.03f, 0.3f}) {
      const TriangleMesh soup = randomSoup(3000, size, seed);
      const std::vector<Ray> rays = mixedRays(soup, 4000, seed + 100);
      const bench::EmbreeRun run = bench::runEmbree(soup.view(), rays, 2, 0, 1);
      ASSERT_EQ(run.hits.size(), rays.size());
      const EmbreeAgreement agreement = compareWithEmbree(soup.view(), rays, run.hits);
      EXPECT_EQ(agreement.mismatches, 0u) << agreement.firstMismatch;
      EXPECT_LE(agreement.tolerated, rays.size() / 200) << "ties and grazing hits should be rare in a random soup";
      EXPECT_GE(agreement.hits, 0.4 * rays.size()) << agreement.hits << " of " << rays.size();
    }
}

TEST(EmbreeReference, ConvertedTreeIsWellFormedAndNearReferenceSah) {
  if (!bench::embreeAvailable()) GTEST_SKIP() << "built without Embree";
  for (uint32_t count : {0u, 1u, 3u, 5u, 1000u, 20000u}) {
    const TriangleMesh soup = randomSoup(count, 0.05f, count);
    const PrimitiveBounds input = triangleBounds(soup.view());
    const bench::EmbreeRun run = bench::runEmbree(soup.view(), {}, 2, 0, 2);
    EXPECT_EQ(run.sceneBuildSeconds.size(), 2u);
    EXPECT_EQ(run.bvhBuildSeconds.size(), 2u);
    EXPECT_EQ(run.traceSeconds.size(), 2u);
    ASSERT_EQ(structuralProblem(run.bvh, input.bounds, 4), "") << count << " triangles";
    const double reference = sahCost(buildReferenceSah(input.bounds, input.centroids));
    EXPECT_LE(sahCost(run.bvh), 1.3 * reference) << count << " triangles";
  }
}

TEST(EmbreeReference, UntraceableRaysMiss) {
  if (!bench::embreeAvailable()) GTEST_SKIP() << "built without Embree";
  const TriangleMesh soup = randomSoup(100, 0.3f, 5);
  const std::vector<Ray> rays{
      Ray{{0.5f, 0.5f, 2.0f}, {0.0f, 0.0f, 0.0f}},
      Ray{{0.5f, 0.5f, 2.0f}, {std::numeric_limits<float>::quiet_NaN(), 0.0f, -1.0f}},
      Ray{{0.5f, 0.5f, 2.0f}, {0.0f, 0.0f, -1.0f}, 1.0f, 0.5f},  // empty interval
  };
  const bench::EmbreeRun run = bench::runEmbree(soup.view(), rays, 1, 0, 1);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(run.hits[i].triangle, HMB_NO_HIT) << "ray " << i;
    EXPECT_EQ(run.hits[i].objectId, HMB_NO_HIT) << "ray " << i;
  }
}

}  // namespace
}  // namespace hmb::bvh::test
