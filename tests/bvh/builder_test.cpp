// The reference builder: a well-formed tree over every primitive on ordinary and degenerate
// inputs, the SAH cost it is judged by, and a cost no worse than a median split.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "bvh/reference_builder.h"
#include "scenes/procedural/mesh_builders.h"
#include "tests/bvh/bvh_test_support.h"

namespace hmb::bvh::test {
namespace {

// Random boxes: centres in the unit cube, half extents up to `size` (0: points).
PrimitiveBounds randomBoxes(uint32_t count, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  PrimitiveBounds out;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 centre(unit(rng), unit(rng), unit(rng));
    const glm::vec3 half = size * glm::vec3(unit(rng), unit(rng), unit(rng));
    out.bounds.push_back(Aabb{centre - half, centre + half});
    out.centroids.push_back(out.bounds.back().center());
  }
  return out;
}

PrimitiveBounds copies(const Aabb& box, uint32_t count) {
  return {std::vector<Aabb>(count, box), std::vector<glm::vec3>(count, box.center())};
}

TEST(ReferenceBuilder, EmptyInputGivesAnEmptyBvh) {
  const Bvh bvh = buildReferenceSah({}, {});
  EXPECT_TRUE(bvh.nodes.empty());
  EXPECT_TRUE(bvh.primitiveIndices.empty());
  EXPECT_EQ(sahCost(bvh), 0.0);
  EXPECT_EQ(depthOf(bvh), 0u);
}

TEST(ReferenceBuilder, OnePrimitiveIsOneLeaf) {
  const PrimitiveBounds input = randomBoxes(1, 0.1f, 1);
  const Bvh bvh = buildReferenceSah(input.bounds, input.centroids);
  ASSERT_EQ(bvh.nodes.size(), 1u);
  EXPECT_EQ(bvh.nodes[0].count, 1u);
  EXPECT_EQ(bvh.primitiveIndices, std::vector<uint32_t>{0});
  EXPECT_EQ(structuralProblem(bvh, input.bounds, 1), "");
  EXPECT_DOUBLE_EQ(sahCost(bvh), 1.0);
}

TEST(ReferenceBuilder, MismatchedInputsThrow) {
  const PrimitiveBounds input = randomBoxes(3, 0.1f, 1);
  EXPECT_THROW(buildReferenceSah(input.bounds, std::span(input.centroids).first(2)), std::invalid_argument);
}

// Two unit cubes at x in [0, 1] and [2, 3]: root area 2 * (3 + 1 + 3) = 14, each leaf 6.
TEST(ReferenceBuilder, SahCostMatchesAHandComputedTreeAndDecidesLeaves) {
  const std::vector<Aabb> boxes{{{0, 0, 0}, {1, 1, 1}}, {{2, 0, 0}, {3, 1, 1}}};
  const std::vector<glm::vec3> centres{boxes[0].center(), boxes[1].center()};
  const Bvh split = buildReferenceSah(boxes, centres, BuildOptions{2, 1.0f, 1.0f});
  ASSERT_EQ(split.nodes.size(), 3u) << "splitting costs 1 + 12/14 < 2 for a leaf";
  EXPECT_NEAR(sahCost(split, {1.0, 1.0}), 1.0 + 12.0 / 14.0, 1e-12);
  EXPECT_NEAR(sahCost(split, {0.5, 2.0}), 0.5 + 2.0 * 12.0 / 14.0, 1e-12);
  // Dearer traversal: a leaf of 2 (cost 2) beats 3 + 12/14; a cap of 1 forces the split anyway.
  EXPECT_EQ(buildReferenceSah(boxes, centres, BuildOptions{2, 3.0f, 1.0f}).nodes.size(), 1u);
  EXPECT_EQ(buildReferenceSah(boxes, centres, BuildOptions{1, 3.0f, 1.0f}).nodes.size(), 3u);
}

TEST(ReferenceBuilder, EveryPrimitiveOnceAndEveryNodeBoundsItsContents) {
  for (uint32_t count : {2u, 3u, 5u, 17u, 100u, 1000u, 20000u})
    for (uint32_t maxLeafSize : {1u, 4u, 8u})
      for (float size : {0.0f, 0.01f, 0.3f}) {
        const PrimitiveBounds input = randomBoxes(count, size, count * 31 + maxLeafSize);
        const Bvh bvh = buildReferenceSah(input.bounds, input.centroids, BuildOptions{maxLeafSize});
        EXPECT_EQ(structuralProblem(bvh, input.bounds, maxLeafSize), "")
            << count << " primitives, leaves up to " << maxLeafSize << ", size " << size;
        EXPECT_TRUE(std::isfinite(sahCost(bvh)));
      }
}

// The checker the other tests rely on must notice each kind of damage.
TEST(ReferenceBuilder, StructuralCheckerCatchesDamage) {
  const PrimitiveBounds input = randomBoxes(200, 0.05f, 7);
  const Bvh good = buildReferenceSah(input.bounds, input.centroids);
  ASSERT_EQ(structuralProblem(good, input.bounds, 4), "");
  const auto firstLeaf = [](const Bvh& bvh) {
    for (size_t i = 0; i < bvh.nodes.size(); ++i)
      if (isLeaf(bvh.nodes[i])) return i;
    return size_t{0};
  };
  Bvh duplicated = good;
  duplicated.primitiveIndices[1] = duplicated.primitiveIndices[0];
  EXPECT_NE(structuralProblem(duplicated, input.bounds, 4), "");
  Bvh shrunk = good;
  Node& leaf = shrunk.nodes[firstLeaf(shrunk)];
  leaf.maxX = leaf.minX;
  EXPECT_NE(structuralProblem(shrunk, input.bounds, 4), "");
  Bvh dangling = good;
  dangling.nodes[0].leftOrFirst = static_cast<uint32_t>(dangling.nodes.size());
  EXPECT_NE(structuralProblem(dangling, input.bounds, 4), "");
  uint32_t largestLeaf = 0;
  for (const Node& node : good.nodes) largestLeaf = std::max(largestLeaf, node.count);
  ASSERT_GE(largestLeaf, 2u);
  EXPECT_NE(structuralProblem(good, input.bounds, largestLeaf - 1), "");
}

// All centroids equal: no position along any axis separates them, yet leaves stay small and
// the tree balanced (ties go to the middle split), with no NaN from zero areas.
TEST(ReferenceBuilder, CoincidentPrimitivesGiveABalancedTree) {
  for (const Aabb& box : {Aabb{{1, 2, 3}, {1.5f, 2.5f, 3.5f}}, Aabb{{1, 2, 3}, {1, 2, 3}}}) {
    const PrimitiveBounds input = copies(box, 100000);
    const Bvh bvh = buildReferenceSah(input.bounds, input.centroids);
    EXPECT_EQ(structuralProblem(bvh, input.bounds, 4), "");
    EXPECT_LE(depthOf(bvh), 17u);  // ceil(log2(100000 / 4)) + 1 = 16 for a perfect split
    EXPECT_TRUE(std::isfinite(sahCost(bvh)));
  }
}

// Zero-area boxes (points, and flat boxes in one plane), and primitives all on one line.
TEST(ReferenceBuilder, DegenerateBoxesBuildWithoutNaN) {
  std::vector<PrimitiveBounds> inputs{randomBoxes(5000, 0.0f, 3)};
  PrimitiveBounds flat = randomBoxes(5000, 0.02f, 4), line = randomBoxes(5000, 0.0f, 5);
  for (size_t i = 0; i < flat.bounds.size(); ++i) {
    flat.bounds[i].min.z = flat.bounds[i].max.z = 0.25f;
    flat.centroids[i].z = 0.25f;
    line.bounds[i].min.y = line.bounds[i].max.y = line.bounds[i].min.z = line.bounds[i].max.z = 0.0f;
    line.centroids[i].y = line.centroids[i].z = 0.0f;
  }
  inputs.push_back(flat);
  inputs.push_back(line);
  for (const PrimitiveBounds& input : inputs) {
    const Bvh bvh = buildReferenceSah(input.bounds, input.centroids);
    EXPECT_EQ(structuralProblem(bvh, input.bounds, 4), "");
    EXPECT_TRUE(std::isfinite(sahCost(bvh)));
    EXPECT_LE(depthOf(bvh), 40u);
  }
}

void expectSahNoWorseThanMedian(const char* name, const PrimitiveBounds& input) {
  const Bvh sah = buildReferenceSah(input.bounds, input.centroids);
  const Bvh median = buildMedianSplit(input.bounds, input.centroids, 4);
  ASSERT_EQ(structuralProblem(median, input.bounds, 4), "") << name;
  const double sahValue = sahCost(sah), medianValue = sahCost(median);
  std::printf("[ SAH cost ] %-28s %7zu prims: full sweep %8.3f, median split %8.3f (%.3fx)\n", name,
              input.bounds.size(), sahValue, medianValue, medianValue / sahValue);
  EXPECT_LE(sahValue, medianValue) << name;
}

TEST(ReferenceBuilder, SahCostNoWorseThanMedianSplit) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    expectSahNoWorseThanMedian("uniform boxes", randomBoxes(20000, 0.01f, seed));
    expectSahNoWorseThanMedian("small triangles", triangleBounds(randomSoup(20000, 0.02f, seed).view()));
    expectSahNoWorseThanMedian("long triangles", triangleBounds(randomSoup(5000, 0.5f, seed).view()));
  }
  // Clusters of very different density: where a median split wastes the most.
  PrimitiveBounds clustered = randomBoxes(10000, 0.002f, 9);
  for (size_t i = 0; i < 9000; ++i) {
    clustered.bounds[i].min = clustered.bounds[i].min * 0.05f + 0.6f;
    clustered.bounds[i].max = clustered.bounds[i].max * 0.05f + 0.6f;
    clustered.centroids[i] = clustered.bounds[i].center();
  }
  expectSahNoWorseThanMedian("clustered boxes", clustered);
  TriangleMesh shapes;
  shapes.append(scene::procedural::makeSphere(1.0f, 64, 32, 0), glm::mat4(1.0f), 1);
  shapes.append(scene::procedural::makeTorus(2.0f, 0.3f, 96, 24, 0), glm::mat4(1.0f), 2);
  expectSahNoWorseThanMedian("sphere + torus", triangleBounds(shapes.view()));
}

TEST(ReferenceBuilder, HundredThousandTrianglesBuildIteratively) {
  const TriangleMesh soup = randomSoup(100000, 0.01f, 11);
  const PrimitiveBounds input = triangleBounds(soup.view());
  const auto start = std::chrono::steady_clock::now();
  const Bvh bvh = buildReferenceSah(input.bounds, input.centroids);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ build    ] 100000 triangles: %.3f s, %zu nodes, depth %u, SAH %.3f\n", seconds, bvh.nodes.size(),
              depthOf(bvh), sahCost(bvh));
  EXPECT_EQ(structuralProblem(bvh, input.bounds, 4), "");
}

}  // namespace
}  // namespace hmb::bvh::test
