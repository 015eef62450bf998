// The treelet builder (passes::TreeletBuild, kernels/bvh/treelet_*.comp), the mesh builder
// under the GPU profile, against its C++ reference (bvh/radix_tree.h): codes within the
// division's rounding, a stable sort, and the same tree bit for bit over the sorted order; well
// formed trees of every size, several trees in one build, a constant number of dispatches and no
// host wait, refits, traversal as brute force, and an SAH cost within kMaxSahRatio of the full
// sweep.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "bvh/radix_tree.h"
#include "bvh/reference_builder.h"
#include "bvh/reference_traversal.h"
#include "hmblur/aabb.h"
#include "hmblur/error.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/bvh_build_pass.h"
#include "runtime/passes/treelet_build.h"
#include "runtime/vulkan/frame_recorder.h"
#include "scenes/reference_scenes.h"
#include "tests/bvh/bvh_test_support.h"
#include "tests/support/vulkan_test.h"
#include "tests/trace/trace_harness.h"

namespace hmb::trace::test {
namespace {

using bvh::test::TriangleMesh;

// The bar for the GPU builder: its trees cost at most this much more than the full
// sweep's by the SAH.
constexpr double kMaxSahRatio = 1.3;

class TreeletBvh : public hmb::test::VulkanTest {
 public:
  static void TearDownTestSuite() { gpuContext().reset(); }

 protected:
  // Builds one tree over all of `boxes` (BvhBox per primitive) in the builder's shape.
  static void buildOne(passes::BvhBuildPass& builder, const vk::Buffer& boxes, uint32_t n) {
    vk::FrameRecorder frame(context());
    const glm::uvec2 root(0u, n);
    builder.build(frame, boxes, n, std::span(&root, 1));
  }
  static passes::BvhBuildShape shape(bool treelets) {
    passes::BvhBuildShape s = passes::BvhBuildShape::forDevice(context());
    s.treelets = treelets;
    return s;
  }
  // A context under the GPU profile, whose scenes build their meshes with treelets.
  static vk::Context& forcedGpu() {
    std::unique_ptr<vk::Context>& made = gpuContext();
    if (!made) {
      vk::ContextOptions options;
      options.validation = true;
      options.deviceProfile = vk::DeviceProfileChoice::Gpu;
      made = std::make_unique<vk::Context>(options);
    }
    return *made;
  }

 private:
  static std::unique_ptr<vk::Context>& gpuContext() {
    static std::unique_ptr<vk::Context> made;
    return made;
  }
};

// A tree breadth-first from `root` with its leaves' primitives relative to `first` (what
// BvhBuildPass::download makes, here from any nodes: the exact ones or the reference's).
bvh::Bvh canonical(const std::vector<gpu::BvhNode>& nodes, const std::vector<uint32_t>& primitives, uint32_t root,
                   uint32_t first) {
  bvh::Bvh out;
  out.nodes.push_back(nodes.at(root));
  for (size_t i = 0; i < out.nodes.size(); ++i) {
    bvh::Node node = out.nodes[i];
    if (bvh::isLeaf(node)) {
      out.nodes[i].leftOrFirst = static_cast<uint32_t>(out.primitiveIndices.size());
      for (uint32_t k = 0; k < node.count; ++k) out.primitiveIndices.push_back(primitives.at(node.leftOrFirst + k) - first);
      continue;
    }
    out.nodes[i].leftOrFirst = static_cast<uint32_t>(out.nodes.size());
    out.nodes.push_back(nodes.at(node.leftOrFirst));
    out.nodes.push_back(nodes.at(node.leftOrFirst + 1));
  }
  return out;
}

// "" when both trees are the same bit for bit, else where they first differ.
std::string difference(const bvh::Bvh& device, const bvh::Bvh& reference) {
  if (device.nodes.size() != reference.nodes.size())
    return std::to_string(device.nodes.size()) + " nodes on the device, " + std::to_string(reference.nodes.size()) +
           " in the reference";
  for (size_t i = 0; i < device.nodes.size(); ++i)
    if (std::memcmp(&device.nodes[i], &reference.nodes[i], sizeof(gpu::BvhNode)) != 0)
      return "node " + std::to_string(i) + " differs";
  if (device.primitiveIndices != reference.primitiveIndices) return "the leaves' primitives differ";
  return "";
}

// Builds trees over `boxes` with the treelet shape and checks each against the reference over
// the device's own sorted order: codes within a cell of the host's, stably sorted.
void expectTreesMatchTheReference(const vk::Context& context, const std::vector<Aabb>& boxes,
                                  const std::vector<glm::uvec2>& roots, uint32_t maxLeaf, const std::string& what) {
  const auto n = static_cast<uint32_t>(boxes.size());
  const vk::Buffer buffer = vk::uploadedBuffer(context, passes::bvhBoxes(boxes), "treelet boxes");
  passes::BvhBuildShape treelets = passes::BvhBuildShape::forDevice(context);
  treelets.treelets = true;
  passes::BvhBuildPass builder(context, "treelets", maxLeaf, treelets);
  vk::FrameRecorder frame(context);
  builder.build(frame, buffer, n, roots);
  const std::vector<uint32_t> codes = builder.treeletBuild()->sortedCodes().download<uint32_t>();
  const std::vector<uint32_t> sorted = builder.treeletBuild()->sortedPrimitives().download<uint32_t>();
  const std::vector<gpu::BvhNode> exact = builder.exactNodes().download<gpu::BvhNode>();
  const std::vector<uint32_t> primitives = builder.primitives().download<uint32_t>();
  for (uint32_t r = 0; r < roots.size(); ++r) {
    const glm::uvec2 range = roots[r];
    const std::string tree = what + ", tree " + std::to_string(r) + " of " + std::to_string(range.y);
    const std::span<const Aabb> own(boxes.data() + range.x, range.y);
    const std::vector<uint32_t> hostCodes = bvh::treeletMortonCodes(own);
    std::vector<uint32_t> treeCodes(codes.begin() + range.x, codes.begin() + range.x + range.y);
    std::vector<uint32_t> order, seen(range.y, 0u);
    for (uint32_t k = 0; k < range.y; ++k) {
      const uint32_t primitive = sorted.at(range.x + k) - range.x;
      ASSERT_LT(primitive, range.y) << tree << ": a primitive left its tree's range";
      ASSERT_EQ(seen[primitive]++, 0u) << tree << ": primitive " << primitive << " sorted twice";
      order.push_back(primitive);
      if (k > 0) {
        ASSERT_LE(treeCodes[k - 1], treeCodes[k]) << tree << ": codes out of order at " << k;
        if (treeCodes[k - 1] == treeCodes[k]) {
          ASSERT_LT(order[k - 1], order[k]) << tree << ": equal codes reordered";
        }
      }
      // Vulkan lets the division that scales a centroid be off by 2.5 ulp: a cell at most.
      const glm::ivec3 apart = glm::abs(glm::ivec3(bvh::mortonCell(treeCodes[k])) - glm::ivec3(bvh::mortonCell(hostCodes[primitive])));
      ASSERT_LE(std::max({apart.x, apart.y, apart.z}), 1) << tree << ": primitive " << primitive;
    }
    const bvh::Bvh reference = bvh::buildTreeletTree(own, treeCodes, order, maxLeaf);
    if (range.y == 0) continue;  // an empty tree: its root alone, checked below
    const bvh::Bvh device = canonical(exact, primitives, r, range.x);
    EXPECT_EQ(difference(device, canonical(reference.nodes, reference.primitiveIndices, 0, 0)), "") << tree;
    // (The checker takes no empty box, which an empty primitive's leaf has.)
    if (std::none_of(own.begin(), own.end(), [](const Aabb& b) { return b.empty(); })) {
      EXPECT_EQ(bvh::test::structuralProblem(builder.download(r), own, maxLeaf), "") << tree;
    }
  }
}

TEST_F(TreeletBvh, TreesAreTheHostReferencesBitForBit) {
  for (const uint32_t n : {1u, 2u, 3u, 5u, 9u, 64u, 1000u, 9000u}) {
    const std::vector<Aabb> boxes = bvh::test::randomBoxes(n, n, true);
    expectTreesMatchTheReference(context(), boxes, {{0u, n}}, HMB_BVH_MAX_LEAF, "random " + std::to_string(n));
  }
  // Every centre the same: every code equal, the tree split by places alone.
  const std::vector<Aabb> coincident(500, Aabb{{0, 0, 0}, {1, 1, 1}});
  expectTreesMatchTheReference(context(), coincident, {{0u, 500u}}, HMB_BVH_MAX_LEAF, "coincident");
  // On a line, a flat axis or two; and leaves of one primitive, as a top level's.
  std::vector<Aabb> line;
  for (int i = 0; i < 300; ++i) line.push_back({{float(i), 0, 0}, {float(i) + 0.5f, 0, 0}});
  expectTreesMatchTheReference(context(), line, {{0u, 300u}}, HMB_BVH_MAX_LEAF, "collinear");
  expectTreesMatchTheReference(context(), bvh::test::randomBoxes(700, 3), {{0u, 700u}}, 1u, "leaves of one");
}

TEST_F(TreeletBvh, ManyTreesOfAnySizeBuildTogether) {
  // Empty trees, one-primitive trees, a tree across several tiles, and places outside every tree.
  const std::vector<Aabb> boxes = bvh::test::randomBoxes(HMB_TREELET_TILE * 2 + 200, 17);
  const std::vector<glm::uvec2> roots = {{0u, 0u},  {0u, 1u},   {1u, 2u}, {3u, 0u},
                                         {3u, 3u},  {6u, HMB_TREELET_TILE * 2 + 20}, {HMB_TREELET_TILE * 2 + 40, 150u}};
  expectTreesMatchTheReference(context(), boxes, roots, HMB_BVH_MAX_LEAF, "many trees");
  const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(boxes), "treelet boxes");
  passes::BvhBuildPass builder(context(), "treelets", HMB_BVH_MAX_LEAF, shape(true));
  vk::FrameRecorder frame(context());
  builder.build(frame, buffer, static_cast<uint32_t>(boxes.size()), roots);
  const std::vector<gpu::BvhNode> nodes = builder.downloadNodes();
  for (const uint32_t empty : {0u, 3u}) {
    EXPECT_GT(nodes.at(empty).minX, nodes.at(empty).maxX) << "tree " << empty << ": an empty root";
    EXPECT_TRUE(builder.download(empty).nodes.empty());
  }
  EXPECT_EQ(nodes.at(1).count, 1u);
}

TEST_F(TreeletBvh, ABuildIsNineDispatchesWhateverItsSizeAndWaitsForNothing) {
  for (const uint32_t n : {10u, 5000u, 120000u}) {
    const std::vector<Aabb> boxes = bvh::test::randomBoxes(n, n + 1);
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(boxes), "treelet boxes");
    passes::BvhBuildPass builder(context(), "treelets", HMB_BVH_MAX_LEAF, shape(true));
    vk::FrameRecorder frame(context());
    frame.begin();
    const vk::FrameRecorder::ShapeMark start = frame.mark();
    const glm::uvec2 root(0u, n);
    builder.record(frame, "treelets", buffer, n, std::span(&root, 1));
    const vk::FrameShape recorded = frame.shapeSince(start, vk::FrameRecorder::HostWaitsUntil::Now);
    EXPECT_EQ(recorded.dispatches, passes::kTreeletDispatches) << n;
    EXPECT_EQ(recorded.indirectDispatches, 0u) << n;
    EXPECT_EQ(recorded.hostWaits, 0u) << n;
    frame.submitAndWait();
    const passes::BvhBuildStats& stats = builder.readRecordedCounts();
    const bvh::Bvh tree = builder.download(0);
    EXPECT_EQ(stats.nodes, tree.nodes.size()) << n;
    EXPECT_EQ(stats.levels, bvh::depthOf(tree)) << n;
    EXPECT_LE(stats.levels, HMB_TREELET_MAX_HEIGHT) << n;
    EXPECT_EQ(bvh::test::structuralProblem(tree, boxes, HMB_BVH_MAX_LEAF), "") << n;
    // Built and waited for, the build is timed by stage, its stages within its frame.
    const passes::BvhBuildStats waited = builder.build(frame, buffer, n, std::span(&root, 1));
    if (!context().info().timestamps) continue;
    ASSERT_EQ(waited.stageMilliseconds.size(), std::size(passes::kTreeletStages)) << n;
    double stages = 0.0;
    for (size_t k = 0; k < waited.stageMilliseconds.size(); ++k) {
      EXPECT_EQ(waited.stageMilliseconds[k].first, passes::kTreeletStages[k]);
      EXPECT_GE(waited.stageMilliseconds[k].second, 0.0);
      stages += waited.stageMilliseconds[k].second;
    }
    EXPECT_LE(stages, waited.deviceMilliseconds * 1.0001) << n;
  }
}

TEST_F(TreeletBvh, RefitsBoundTheMovedPrimitives) {
  TriangleMesh mesh = bvh::test::cubeSphere(12);
  const bvh::PrimitiveBounds before = bvh::triangleBounds(mesh.view());
  const auto n = static_cast<uint32_t>(before.bounds.size());
  const vk::Buffer built = vk::uploadedBuffer(context(), passes::bvhBoxes(before.bounds), "treelet boxes");
  passes::BvhBuildPass builder(context(), "treelets", HMB_BVH_MAX_LEAF, shape(true));
  buildOne(builder, built, n);
  for (glm::vec3& p : mesh.positions) p += glm::vec3(0.3f * std::sin(4.0f * p.y), 0.0f, 0.2f * p.x * p.x);
  const bvh::PrimitiveBounds after = bvh::triangleBounds(mesh.view());
  const vk::Buffer moved = vk::uploadedBuffer(context(), passes::bvhBoxes(after.bounds), "moved boxes");
  vk::FrameRecorder frame(context());
  builder.refit(frame, moved);
  EXPECT_EQ(bvh::test::structuralProblem(builder.download(0), after.bounds, HMB_BVH_MAX_LEAF), "");
}

TEST_F(TreeletBvh, ScenesTraceAsBruteForceUnderTheGpuProfile) {
  vk::Context& gpu = forcedGpu();
  const TriangleMesh soup = bvh::test::randomSoup(3000, 0.08f, 11);
  const std::vector<bvh::Ray> rays = bvh::test::mixedRays(soup, 3000, 12);
  const std::vector<gpu::BvhHit> hits = traceMesh(gpu, soup, rays);
  TriangleMesh oneObject = soup;
  oneObject.objectIds.assign(soup.triangleCount(), 1u);
  uint32_t mismatches = 0, hitCount = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const gpu::BvhHit expected = bvh::bruteForceClosestHit(oneObject.view(), rays[i]);
    hitCount += expected.triangle != HMB_NO_HIT;
    const bool same = expected.triangle == hits[i].triangle ||
                      (expected.triangle != HMB_NO_HIT && hits[i].triangle != HMB_NO_HIT &&
                       std::abs(expected.t - hits[i].t) <= 1e-5f * std::max(1.0f, std::abs(expected.t)));
    mismatches += !same;
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GE(hitCount, 1000u);
  // The scene's meshes were built by treelets.
  const scene::Scene scene = sceneOf(soup);
  vk::FrameRecorder frame(gpu);
  const TraceScene traceScene(gpu, scene, frame);
  EXPECT_TRUE(traceScene.meshBvh().shape().treelets);
  EXPECT_EQ(traceScene.meshBvh().stats().submissions, 1u);
}

TEST_F(TreeletBvh, SahCostWithinBoundOfFullSweep) {
  std::vector<std::pair<std::string, TriangleMesh>> meshes;
  for (const std::string& name : scene::referenceSceneNames()) {
    const scene::Scene scene = scene::makeReferenceScene(name);
    meshes.emplace_back(name, bvh::test::sceneTriangles(scene, scene.settings.frameTime));
  }
  meshes.emplace_back("cube sphere", bvh::test::cubeSphere(60));
  meshes.emplace_back("random soup", bvh::test::randomSoup(20000, 0.05f, 9));
  for (const auto& [name, mesh] : meshes) {
    const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh.view());
    const auto n = static_cast<uint32_t>(input.bounds.size());
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "treelet boxes");
    passes::BvhBuildPass builder(context(), "treelets", HMB_BVH_MAX_LEAF, shape(true));
    buildOne(builder, buffer, n);
    const bvh::Bvh device = builder.download(0);
    EXPECT_EQ(bvh::test::structuralProblem(device, input.bounds, HMB_BVH_MAX_LEAF), "") << name;
    const double ratio = bvh::sahCost(device) / bvh::sahCost(bvh::buildReferenceSah(input.bounds, input.centroids));
    std::printf("[ treelets ] %-16s %7u triangles: SAH %.3fx the full sweep's, %u levels\n", name.c_str(), n, ratio,
                builder.stats().levels);
    EXPECT_LE(ratio, kMaxSahRatio) << name;
  }
}

TEST_F(TreeletBvh, OnlyMeshBuildsTakeTreelets) {
  EXPECT_FALSE(passes::BvhBuildShape::forTopLevel(forcedGpu()).treelets);
  EXPECT_TRUE(passes::BvhBuildShape::forDevice(forcedGpu()).treelets);
  passes::BvhBuildPass builder(context(), "treelets", HMB_BVH_MAX_LEAF, shape(true));
  EXPECT_THROW(builder.limitDepth(20), hmb::Error);
  const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(bvh::test::randomBoxes(8, 1)), "boxes");
  vk::FrameRecorder frame(context());
  frame.begin();
  const uint32_t order[] = {0, 1, 2, 3, 4, 5, 6, 7};
  EXPECT_THROW(builder.recordKeptWithInsertions(frame, "kept", buffer, order, 6), hmb::Error);
}

}  // namespace
}  // namespace hmb::trace::test
