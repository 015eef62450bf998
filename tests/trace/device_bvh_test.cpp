// The device BVH builder (kernels/bvh/) against the CPU yardsticks: every tree is well formed
// (each primitive in exactly one leaf, every node bounding its children), no node deeper than
// HMB_BVH_MAX_DEPTH, and its SAH cost within kMaxSahRatio of the full-sweep SAH build (scenes
// build with the profile's builder: under the GPU profile the treelet builder, whose bound is
// kMaxTreeletSahRatio; the tests of levels and small tasks take the binned shape).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

#include "bvh/packed_node.h"
#include "bvh/reference_builder.h"
#include "hmblur/error.h"
#include "kernels/shared/dispatch.h"
#include "runtime/vulkan/frame_recorder.h"
#include "scenes/reference_scenes.h"
#include "tests/support/vulkan_test.h"
#include "tests/trace/trace_harness.h"

namespace hmb::trace::test {
namespace {

using bvh::test::TriangleMesh;

// The largest SAH cost the device build may have, relative to the CPU full sweep: the binned
// builder's, and the treelet builder's (the mesh builder under the GPU profile).
constexpr double kMaxSahRatio = 1.15;
constexpr double kMaxTreeletSahRatio = 1.3;

class DeviceBvh : public hmb::test::VulkanTest {
 protected:
  // The binned builder's shape on this device, whatever the profile builds meshes with: the
  // tests of its levels, small tasks and depth bounds (tests/trace/treelet_bvh_test.cpp tests
  // the treelet builder).
  static passes::BvhBuildShape binned() {
    passes::BvhBuildShape shape = passes::BvhBuildShape::forDevice(context());
    shape.treelets = false;
    return shape;
  }
  // Scenes build their meshes with the profile's builder.
  static bool scenesBuildTreelets() { return passes::BvhBuildShape::forDevice(context()).treelets; }
  static double maxSahRatio() { return scenesBuildTreelets() ? kMaxTreeletSahRatio : kMaxSahRatio; }

  // Builds on the device and checks the tree against the mesh; returns its SAH ratio.
  double checkBuild(const TriangleMesh& mesh, const std::string& what) {
    const scene::Scene scene = sceneOf(mesh);
    vk::FrameRecorder frame(context());
    const auto start = std::chrono::steady_clock::now();
    const TraceScene traceScene(context(), scene, frame);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (mesh.triangleCount() == 0) {
      // An empty tree is its root alone, with an empty box: traversal never enters it.
      const std::vector<gpu::BvhNode> nodes = traceScene.meshBvh().downloadNodes();
      EXPECT_GT(nodes.at(0).minX, nodes.at(0).maxX) << what;
      return 1.0;
    }
    const bvh::Bvh device = traceScene.meshBvh().download(0);
    const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh.view());
    EXPECT_EQ(bvh::test::structuralProblem(device, input.bounds, HMB_BVH_MAX_LEAF), "") << what;
    EXPECT_LE(levelsBelowRoot(device), HMB_BVH_MAX_DEPTH) << what;
    const bvh::Bvh reference = bvh::buildReferenceSah(input.bounds, input.centroids);
    const double ratio = bvh::sahCost(device) / bvh::sahCost(reference);
    const passes::BvhBuildStats& stats = traceScene.meshBvh().stats();
    std::printf("[ device   ] %-24s %8u triangles: SAH %.3f vs full sweep %.3f (%.3fx), %u levels, %u submissions, "
                "device %.1f ms, wall %.3f s\n",
                what.c_str(), mesh.triangleCount(), bvh::sahCost(device), bvh::sahCost(reference), ratio,
                stats.levels, stats.submissions, stats.deviceMilliseconds, seconds);
    return ratio;
  }
};

TEST_F(DeviceBvh, SmallAndDegenerateMeshesAreWellFormed) {
  checkBuild(TriangleMesh{}, "no triangles");  // a fresh builder's first build is empty (glTF files of points)
  checkBuild(bvh::test::randomSoup(1, 0.1f, 1), "one triangle");
  checkBuild(bvh::test::randomSoup(2, 0.1f, 2), "two triangles");
  checkBuild(bvh::test::randomSoup(5, 0.1f, 3), "five triangles");
  TriangleMesh coincident;  // every centroid equal: only the median fallback can split them
  for (int i = 0; i < 100; ++i) coincident.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
  checkBuild(coincident, "100 coincident");
  TriangleMesh degenerate;  // zero-area triangles: points and segments, some repeated
  for (int i = 0; i < 50; ++i) {
    const float x = float(i % 7);
    degenerate.addTriangle({x, 0, 0}, {x, 0, 0}, {x, 0, 0}, 1);
    degenerate.addTriangle({x, 1, 0}, {x + 1, 1, 0}, {x + 2, 1, 0}, 1);
  }
  checkBuild(degenerate, "degenerate");
  TriangleMesh line;  // all on one line: the root has no area
  for (int i = 0; i < 40; ++i) line.addTriangle({float(i), 0, 0}, {float(i) + 0.5f, 0, 0}, {float(i) + 1, 0, 0}, 1);
  checkBuild(line, "collinear");
}

TEST_F(DeviceBvh, ATreeDeeperThanTheFirstBatchOfLevelsIsFinishedInLaterSubmissions) {
  // Triangles at x = 2^i: binned over the centroids' span, each split peels off the largest
  // few, so the tree is far deeper than log2 of its size and outgrows the first submission.
  TriangleMesh spread;
  for (int i = 0; i < 60; ++i) {
    const float x = std::ldexp(1.0f, i);
    spread.addTriangle({x, 0, 0}, {x, 1, 0}, {x, 0, 1}, 1);
  }
  checkBuild(spread, "exponentially spread");
  const bvh::PrimitiveBounds input = bvh::triangleBounds(spread.view());
  const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "spread boxes");
  passes::BvhBuildPass builder(context(), "spread", HMB_BVH_MAX_LEAF, binned());
  vk::FrameRecorder frame(context());
  const glm::uvec2 root(0u, spread.triangleCount());
  const passes::BvhBuildStats& stats = builder.build(frame, buffer, spread.triangleCount(), std::span(&root, 1));
  EXPECT_GT(stats.levels, passes::BvhBuildPass::firstSubmissionLevels(spread.triangleCount()));
  EXPECT_GE(stats.submissions, 2u);
  EXPECT_EQ(stats.leaves, builder.download(0).nodes.size() / 2 + 1);
  EXPECT_EQ(bvh::test::structuralProblem(builder.download(0), input.bounds, HMB_BVH_MAX_LEAF), "");
}

// Triangles along the x axis, each 1.6 times as far out and as large as the one before: the
// SAH peels a few of the largest off at each level, a tree several times deeper than a
// balanced one.
TriangleMesh geometricChain(uint32_t count) {
  TriangleMesh mesh;
  double x = 1e-9;
  for (uint32_t i = 0; i < count; ++i, x *= 1.6) {
    const auto w = static_cast<float>(0.1 * x);
    const glm::vec3 corner(static_cast<float>(x), 0.0f, 0.0f);
    mesh.addTriangle(corner, corner + glm::vec3(w, 0.0f, 0.0f), corner + glm::vec3(0.0f, w, 0.0f), 1);
  }
  return mesh;
}

// Traversal keeps one pending subtree per level and nothing past that, so the build bounds
// every tree's depth (HMB_BVH_MAX_DEPTH). No SAH tree of a float scene has come near 64 levels,
// so the bound is checked here tighter than the trees' own depth: in the level-by-level
// splits (the chain's first levels hold more than HMB_BVH_SMALL_TASK triangles) and in the
// small tasks' subtrees.
TEST_F(DeviceBvh, TreesStayWithinTheDepthBound) {
  // 120 triangles: the bound binds first in build_level; 60: in build_small_tasks (the root's
  // children are small tasks). Each needs 7 or 6 halvings.
  for (const auto& [triangles, bound] : {std::pair{120u, 10u}, std::pair{60u, 7u}}) {
    const TriangleMesh chain = geometricChain(triangles);
    const bvh::PrimitiveBounds input = bvh::triangleBounds(chain.view());
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "chain boxes");
    const glm::uvec2 roots[] = {{0u, triangles}};
    vk::FrameRecorder frame(context());
    passes::BvhBuildPass unbounded(context(), "chain", HMB_BVH_MAX_LEAF, binned());
    unbounded.build(frame, buffer, triangles, roots);
    const uint32_t ownDepth = levelsBelowRoot(unbounded.download(0));
    ASSERT_GT(ownDepth, bound + 8) << triangles;
    passes::BvhBuildPass bounded(context(), "bounded chain", HMB_BVH_MAX_LEAF, binned());
    bounded.limitDepth(bound);
    bounded.build(frame, buffer, triangles, roots);
    const bvh::Bvh tree = bounded.download(0);
    EXPECT_EQ(bvh::test::structuralProblem(tree, input.bounds, HMB_BVH_MAX_LEAF), "") << triangles;
    EXPECT_LE(levelsBelowRoot(tree), bound) << triangles;
    std::printf("[ depth    ] geometric chain, %u triangles: %u levels below the root, %u under a bound of %u\n",
                triangles, ownDepth, levelsBelowRoot(tree), bound);
    // A bound the tree cannot keep even when halved throughout is refused.
    bounded.limitDepth(bound - 4);
    EXPECT_THROW(bounded.build(frame, buffer, triangles, roots), hmb::Error) << triangles;
  }
  passes::BvhBuildPass builder(context(), "any", HMB_BVH_MAX_LEAF);
  EXPECT_THROW(builder.limitDepth(HMB_BVH_MAX_DEPTH + 1), hmb::Error);
}

// Two builds' trees node for node: the same bounds and counts, and each leaf the same
// primitives, in any order (a partition may order a leaf's primitives differently).
void expectSameTree(const bvh::Bvh& a, const bvh::Bvh& b, uint32_t tree) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size()) << "tree " << tree;
  const auto leaf = [](const bvh::Bvh& t, size_t i) {
    std::vector<uint32_t> in(t.primitiveIndices.begin() + t.nodes[i].leftOrFirst,
                             t.primitiveIndices.begin() + t.nodes[i].leftOrFirst + t.nodes[i].count);
    std::sort(in.begin(), in.end());
    return in;
  };
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    ASSERT_EQ(bvh::boundsOf(a.nodes[i]).min, bvh::boundsOf(b.nodes[i]).min) << "tree " << tree << " node " << i;
    ASSERT_EQ(bvh::boundsOf(a.nodes[i]).max, bvh::boundsOf(b.nodes[i]).max) << "tree " << tree << " node " << i;
    ASSERT_EQ(a.nodes[i].count, b.nodes[i].count) << "tree " << tree << " node " << i;
    if (bvh::isLeaf(a.nodes[i])) {
      ASSERT_EQ(leaf(a, i), leaf(b, i)) << "tree " << tree << " leaf " << i;
    }
  }
}

// A build recorded into a frame (no submission, no read-back: an engine's per-frame top
// level) makes the trees build() makes under the same depth bound, node for node, and
// finishes within the levels it records even where the SAH alone would go far deeper: the
// geometric chain of 120 keeps a task too large for build_small_tasks down to the last level
// recorded (one level fewer leaves it unbuilt). Its counts are read back on request.
TEST_F(DeviceBvh, ARecordedBuildIsTheWaitedBuildUnderItsDepthBound) {
  const TriangleMesh soup = bvh::test::randomSoup(5000, 0.05f, 41), chain = geometricChain(120);
  for (const TriangleMesh* mesh : {&soup, &chain}) {
    const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh->view());
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "boxes");
    const auto count = static_cast<uint32_t>(input.bounds.size());
    std::vector<glm::uvec2> roots = {{0u, count}};
    if (mesh == &soup) roots = {{0u, count / 4}, {count / 4, count - count / 4}};
    uint32_t largest = 0;
    for (const glm::uvec2& root : roots) largest = std::max(largest, root.y);
    vk::FrameRecorder frame(context());
    passes::BvhBuildPass recorded(context(), "recorded", HMB_BVH_MAX_LEAF, binned());
    const uint32_t bound = recorded.recordedDepthBound(largest);
    const uint64_t waits = context().hostWaits(), readbacks = context().hostReadbacks();
    frame.begin();
    recorded.record(frame, "a recorded build", buffer, count, roots);
    EXPECT_EQ(context().hostWaits(), waits);
    EXPECT_EQ(context().hostReadbacks(), readbacks);
    const vk::FrameTimings timings = frame.submitAndWait();
    for (const vk::PassTiming& pass : timings.passes) EXPECT_EQ(pass.name, "a recorded build");
    const passes::BvhBuildStats& stats = recorded.readRecordedCounts();
    EXPECT_LE(stats.levels, bound + 1);  // the root counts as a level

    passes::BvhBuildPass waited(context(), "waited", HMB_BVH_MAX_LEAF, binned());
    waited.limitDepth(bound);
    waited.build(frame, buffer, count, roots);
    // A level left out leaves a task unsplit: fewer nodes (and garbage below it, not walked).
    ASSERT_EQ(stats.nodes, waited.stats().nodes);
    ASSERT_EQ(stats.leaves, waited.stats().leaves);
    for (uint32_t r = 0; r < roots.size(); ++r) {
      const bvh::Bvh a = recorded.download(r), b = waited.download(r);
      EXPECT_EQ(bvh::test::structuralProblem(a, std::span(input.bounds).subspan(roots[r].x, roots[r].y),
                                             HMB_BVH_MAX_LEAF),
                "")
          << "tree " << r;
      EXPECT_LE(levelsBelowRoot(a), bound) << "tree " << r;
      expectSameTree(a, b, r);
    }
  }
}

TEST_F(DeviceBvh, LeavesHoldNoMorePrimitivesThanTheBuildAllows) {
  // Six coincident boxes: no split is cheaper than a leaf, so only the limit divides them
  // (median splits: 3 + 3 under a limit of 4, down to single boxes under a limit of 1).
  const std::vector<gpu::BvhBox> boxes(6, gpu::BvhBox{glm::vec4(0.0f), glm::vec4(1.0f, 1.0f, 1.0f, 0.0f)});
  const std::vector<Aabb> bounds(boxes.size(), Aabb{glm::vec3(0.0f), glm::vec3(1.0f)});
  const vk::Buffer buffer = vk::uploadedBuffer(context(), boxes, "coincident boxes");
  for (const uint32_t maxLeaf : {HMB_BVH_MAX_INSTANCE_LEAF, HMB_BVH_MAX_LEAF}) {
    passes::BvhBuildPass builder(context(), "limited leaves", maxLeaf, binned());
    vk::FrameRecorder frame(context());
    const glm::uvec2 root(0u, 6u);
    builder.build(frame, buffer, 6u, std::span(&root, 1));
    const bvh::Bvh tree = builder.download(0);
    EXPECT_EQ(bvh::test::structuralProblem(tree, bounds, maxLeaf), "") << "leaves of " << maxLeaf;
    uint32_t largest = 0;
    for (const bvh::Node& node : tree.nodes)
      if (bvh::isLeaf(node)) largest = std::max(largest, node.count);
    EXPECT_EQ(largest, std::min(maxLeaf, 3u)) << "leaves of " << maxLeaf;
  }
}

TEST_F(DeviceBvh, CompactingKeepsTheTreesInBuffersOfTheirSizeAndABuildMayFollow) {
  const TriangleMesh mesh = bvh::test::randomSoup(500, 0.05f, 11);
  const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh.view());
  const std::vector<gpu::BvhBox> boxes = passes::bvhBoxes(input.bounds);
  const vk::Buffer buffer = vk::uploadedBuffer(context(), boxes, "soup boxes");
  const auto count = static_cast<uint32_t>(boxes.size());
  const glm::uvec2 roots[] = {{0u, count / 2}, {count / 2, count - count / 2}};
  passes::BvhBuildPass builder(context(), "compacted", HMB_BVH_MAX_LEAF);
  vk::FrameRecorder frame(context());
  builder.build(frame, buffer, count, roots);
  const bvh::Bvh before = builder.download(1);
  builder.compact(frame);
  EXPECT_EQ(builder.allocatedTreeBytes(), builder.usedTreeBytes());
  const bvh::Bvh after = builder.download(1);
  ASSERT_EQ(after.nodes.size(), before.nodes.size());
  for (size_t i = 0; i < after.nodes.size(); ++i) {
    EXPECT_EQ(bvh::boundsOf(after.nodes[i]).min, bvh::boundsOf(before.nodes[i]).min) << "node " << i;
    EXPECT_EQ(bvh::boundsOf(after.nodes[i]).max, bvh::boundsOf(before.nodes[i]).max) << "node " << i;
  }
  EXPECT_EQ(after.primitiveIndices, before.primitiveIndices);
  // The buffers were fitted to these trees; a build over all the boxes as one tree regrows them.
  const glm::uvec2 whole(0u, count);
  builder.build(frame, buffer, count, std::span(&whole, 1));
  EXPECT_EQ(bvh::test::structuralProblem(builder.download(0), input.bounds, HMB_BVH_MAX_LEAF), "");
}

// The workgroup shape is the device's (CPU: 8 lanes, per-lane bins; GPU: a warp or wave,
// shared atomics), and both must make the same trees: the bins' counts and bounds do not
// depend on who adds what. Here both run on the test device, over two trees of each of two
// soups (large tasks bin per lane in the CPU shape). Node numbering and the order of
// primitives inside a leaf may differ (atomics hand out places in any order); every node's
// bounds, the shape of the tree and each leaf's primitive set may not. (Where centroids tie
// along an axis, the small subtrees' sorts keep the order the levels left, so a mesh with
// such ties, like the cube sphere, may split its tied primitives the other way round.)
TEST_F(DeviceBvh, GpuAndCpuShapedBuildsMakeTheSameTrees) {
  const passes::BvhBuildShape cpu{HMB_BVH_LEVEL_GROUP, true}, gpu{32, false};
  EXPECT_EQ(cpu.describe(), "8 lanes, per-lane bins");
  EXPECT_EQ(gpu.describe(), "32 lanes, shared atomics");
  for (const TriangleMesh& mesh : {bvh::test::randomSoup(20000, 0.02f, 31), bvh::test::randomSoup(3000, 0.2f, 32)}) {
    const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh.view());
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "boxes");
    const auto count = static_cast<uint32_t>(input.bounds.size());
    const glm::uvec2 roots[] = {{0u, count / 3}, {count / 3, count - count / 3}};
    std::vector<bvh::Bvh> trees[2];
    for (int s = 0; s < 2; ++s) {
      passes::BvhBuildPass builder(context(), "shaped", HMB_BVH_MAX_LEAF, s == 0 ? cpu : gpu);
      vk::FrameRecorder frame(context());
      builder.build(frame, buffer, count, roots);
      for (uint32_t r = 0; r < 2; ++r) trees[s].push_back(builder.download(r));
    }
    for (uint32_t r = 0; r < 2; ++r) expectSameTree(trees[0][r], trees[1][r], r);
  }
}

std::vector<gpu::BvhBox> boxesOf(const TriangleMesh& mesh) {
  return passes::bvhBoxes(bvh::triangleBounds(mesh.view()).bounds);
}

// The mesh bent and swollen: every triangle moves, many change size and orientation.
TriangleMesh deformed(TriangleMesh mesh) {
  for (glm::vec3& p : mesh.positions)
    p = glm::vec3(p.x * (1.0f + 0.4f * std::sin(3.0f * p.y)), p.y + 0.3f * p.x * p.x, p.z * (1.2f - 0.5f * p.y));
  return mesh;
}

// Refit of kept trees to deformed triangles (built once, refitted, compacted, refitted again):
// every tree stays well formed over the new boxes (each node bounds its children and
// primitives), traversal of the refitted tree agrees with brute force over the deformed
// triangles, a one-primitive tree and an empty one come through, and the SAH drift against a
// fresh build of the deformed mesh is reported.
TEST_F(DeviceBvh, RefitBoundsDeformedTrianglesWithTheTopologyKept) {
  const TriangleMesh mesh = bvh::test::cubeSphere(14);
  const TriangleMesh bent = deformed(mesh);
  const auto count = mesh.triangleCount();
  const vk::Buffer before = vk::uploadedBuffer(context(), boxesOf(mesh), "sphere boxes");
  const vk::Buffer after = vk::uploadedBuffer(context(), boxesOf(bent), "bent sphere boxes");
  const glm::uvec2 roots[] = {{0u, count - 301u}, {count - 301u, 300u}, {count - 1u, 1u}, {count, 0u}};
  passes::BvhBuildPass builder(context(), "refitted", HMB_BVH_MAX_LEAF);
  vk::FrameRecorder frame(context());
  builder.build(frame, before, count, roots);
  const std::vector<gpu::BvhNode> built = builder.downloadNodes();
  const std::vector<Aabb> bentBounds = bvh::triangleBounds(bent.view()).bounds;
  const std::vector<Aabb> restBounds = bvh::triangleBounds(mesh.view()).bounds;
  for (const bool compacted : {false, true}) {
    if (compacted) {
      builder.compact(frame);
      // Refits after the first reuse its parents, depths and order: back to the rest pose and
      // bent again, each bounded right.
      builder.refit(frame, before);
      const std::vector<Aabb> treeBounds(restBounds.begin(), restBounds.begin() + roots[0].y);
      EXPECT_EQ(bvh::test::structuralProblem(builder.download(0), treeBounds, HMB_BVH_MAX_LEAF), "") << "rest pose";
    }
    builder.refit(frame, after);
    for (uint32_t tree = 0; tree < 3; ++tree) {
      const glm::uvec2 range = roots[tree];
      const std::vector<Aabb> treeBounds(bentBounds.begin() + range.x, bentBounds.begin() + range.x + range.y);
      EXPECT_EQ(bvh::test::structuralProblem(builder.download(tree), treeBounds, HMB_BVH_MAX_LEAF), "")
          << "tree " << tree << (compacted ? ", compacted" : "");
    }
    EXPECT_TRUE(builder.download(3).nodes.empty());
    // The topology is the build's: every node's children or primitive range.
    const std::vector<gpu::BvhNode> refitted = builder.downloadNodes();
    ASSERT_EQ(refitted.size(), built.size());
    for (size_t n = 0; n < built.size(); ++n)
      EXPECT_TRUE(refitted[n].leftOrFirst == built[n].leftOrFirst && refitted[n].count == built[n].count) << "node " << n;
  }
  // Tree 0 traced on the host over the deformed triangles of its range, against brute force.
  TriangleMesh first;
  first.positions = bent.positions;
  first.indices.assign(bent.indices.begin(), bent.indices.begin() + 3 * size_t(roots[0].y));
  first.objectIds.assign(roots[0].y, 0u);
  const bvh::Bvh refitted = builder.download(0);
  const bvh::test::Agreement agreement =
      bvh::test::compareWithBruteForce(refitted, first.view(), bvh::test::mixedRays(first, 3000, 17));
  EXPECT_EQ(agreement.mismatches, 0u) << agreement.firstMismatch;
  EXPECT_GE(agreement.hits, 1000u);
  // The drift: the kept topology against a fresh build over the deformed boxes.
  passes::BvhBuildPass fresh(context(), "fresh", HMB_BVH_MAX_LEAF);
  fresh.build(frame, after, count, roots);
  const double drift = bvh::sahCost(refitted) / bvh::sahCost(fresh.download(0));
  std::printf("[ refit    ] bent cube sphere, %u triangles: SAH %.3fx a fresh build's\n", roots[0].y, drift);
  EXPECT_GE(drift, 0.9);

  // A refit of some trees leaves the others as they were, whatever their boxes say.
  builder.refit(frame, before);
  const bvh::Bvh restTree0 = builder.download(0), restTree2 = builder.download(2);
  const uint32_t onlyTree1[] = {1};
  builder.refit(frame, after, onlyTree1);
  const std::vector<Aabb> bentTree1(bentBounds.begin() + roots[1].x, bentBounds.begin() + roots[1].x + roots[1].y);
  EXPECT_EQ(bvh::test::structuralProblem(builder.download(1), bentTree1, HMB_BVH_MAX_LEAF), "") << "tree 1 refitted alone";
  for (const auto& [tree, rest] : {std::pair{0u, &restTree0}, std::pair{2u, &restTree2}}) {
    const bvh::Bvh kept = builder.download(tree);
    ASSERT_EQ(kept.nodes.size(), rest->nodes.size()) << "tree " << tree;
    for (size_t n = 0; n < kept.nodes.size(); ++n) {
      EXPECT_EQ(bvh::boundsOf(kept.nodes[n]).min, bvh::boundsOf(rest->nodes[n]).min) << "tree " << tree << " node " << n;
      EXPECT_EQ(bvh::boundsOf(kept.nodes[n]).max, bvh::boundsOf(rest->nodes[n]).max) << "tree " << tree << " node " << n;
    }
  }
}

TEST_F(DeviceBvh, PackedNodesAreTheHostsPackingOfTheExactNodes) {
  // Trees far from the origin, tiny, flat, of one triangle and of none, built together: each
  // frame and every packed node must be what bvh/packed_node.cpp makes of the exact node.
  std::vector<TriangleMesh> meshes;
  TriangleMesh far = bvh::test::randomSoup(300, 0.05f, 21), tiny = bvh::test::randomSoup(200, 0.05f, 22);
  for (glm::vec3& p : far.positions) p = p * 8.0f + glm::vec3(1e7f, -3e7f, 5e6f);
  for (glm::vec3& p : tiny.positions) p *= 1e-4f;
  meshes = {far, tiny, bvh::test::grid(10, 23), bvh::test::randomSoup(1, 0.1f, 24), TriangleMesh{}};
  std::vector<gpu::BvhBox> boxes;
  std::vector<glm::uvec2> roots;
  for (const TriangleMesh& mesh : meshes) {
    roots.emplace_back(uint32_t(boxes.size()), mesh.triangleCount());
    const std::vector<gpu::BvhBox> meshBoxes = boxesOf(mesh);
    boxes.insert(boxes.end(), meshBoxes.begin(), meshBoxes.end());
  }
  const vk::Buffer buffer = vk::uploadedBuffer(context(), boxes, "packing boxes");
  passes::BvhBuildPass builder(context(), "packed", HMB_BVH_MAX_LEAF);
  vk::FrameRecorder frame(context());
  builder.build(frame, buffer, uint32_t(boxes.size()), roots);
  const auto exact = builder.exactNodes().download<gpu::BvhNode>();
  const auto packed = builder.nodes().download<gpu::BvhPackedNode>();
  const auto frames = builder.frames().download<gpu::BvhFrame>();
  uint32_t visited = 0;
  for (uint32_t tree = 0; tree < roots.size(); ++tree) {
    const gpu::BvhFrame expected = bvh::frameOf(bvh::boundsOf(exact.at(tree)));
    EXPECT_EQ(frames.at(tree).origin, expected.origin) << "tree " << tree;
    EXPECT_EQ(frames.at(tree).step, expected.step) << "tree " << tree;
    for (std::vector<uint32_t> stack{tree}; !stack.empty(); ++visited) {
      const uint32_t index = stack.back();
      stack.pop_back();
      const gpu::BvhNode node = exact.at(index);
      const gpu::BvhPackedNode want = bvh::packNode(node, expected), got = packed.at(index);
      ASSERT_TRUE(got.x == want.x && got.y == want.y && got.z == want.z &&
                  got.leftOrFirstCount == want.leftOrFirstCount)
          << "tree " << tree << ", node " << index;
      if (node.count == 0 && roots[tree].y > 1) stack.insert(stack.end(), {node.leftOrFirst, node.leftOrFirst + 1});
    }
  }
  EXPECT_EQ(visited, builder.stats().nodes);  // every node checked
}

TEST_F(DeviceBvh, NonFiniteTrianglesGetEmptyBoxes) {
  TriangleMesh mesh = bvh::test::randomSoup(200, 0.05f, 4);
  const float inf = std::numeric_limits<float>::infinity();
  mesh.addTriangle({std::nanf(""), 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
  mesh.addTriangle({inf, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
  const scene::Scene scene = sceneOf(mesh);
  vk::FrameRecorder frame(context());
  const TraceScene traceScene(context(), scene, frame);
  const bvh::Bvh device = traceScene.meshBvh().download(0);
  // Every primitive once, and the root's box finite: the broken triangles widen nothing.
  std::vector<int> seen(mesh.triangleCount(), 0);
  for (uint32_t p : device.primitiveIndices) ++seen.at(p);
  for (int count : seen) EXPECT_EQ(count, 1);
  const Aabb root = bvh::boundsOf(device.nodes.at(0));
  EXPECT_TRUE(std::isfinite(root.min.x) && std::isfinite(root.max.x));
  EXPECT_LE(root.max.x, 1.1f);
}

// A tree of at most HMB_BVH_SMALL_TASK primitives goes from begin_build to build_small_tasks
// (a top level over a few instances, a small mesh): no level is dispatched, and the tree is as
// sound and as cheap as the levels make others. Beside a larger tree in the same build, each
// takes its own way.
TEST_F(DeviceBvh, SmallTreesGoStraightToTheSmallTasks) {
  if (scenesBuildTreelets()) GTEST_SKIP() << "scenes build their meshes by treelets under this profile: no small tasks";
  for (const uint32_t n : {2u, 17u, HMB_BVH_SMALL_TASK}) {
    const TriangleMesh mesh = bvh::test::randomSoup(n, 0.1f, 40 + n);
    vk::FrameRecorder frame(context());
    const TraceScene traceScene(context(), sceneOf(mesh), frame);
    const passes::BvhBuildStats& stats = traceScene.meshBvh().stats();
    EXPECT_TRUE(stats.levelMilliseconds.empty()) << n << " triangles: " << stats.levelMilliseconds.size() << " levels";
    EXPECT_EQ(stats.smallTasks, 1u) << n << " triangles";
    EXPECT_LE(checkBuild(mesh, std::to_string(n) + " triangles, small"), maxSahRatio());
  }
  scene::Scene scene;
  const std::vector<TriangleMesh> meshes = {bvh::test::randomSoup(HMB_BVH_SMALL_TASK, 0.1f, 3),
                                            bvh::test::randomSoup(HMB_BVH_SMALL_TASK + 1, 0.1f, 4)};
  for (const TriangleMesh& mesh : meshes) {
    scene::Mesh m;
    m.positions = mesh.positions;
    m.indices = mesh.indices;
    scene.meshes.push_back(m);
  }
  vk::FrameRecorder frame(context());
  const TraceScene traceScene(context(), scene, frame);
  EXPECT_FALSE(traceScene.meshBvh().stats().levelMilliseconds.empty()) << "the larger tree needs its levels";
  for (uint32_t m = 0; m < meshes.size(); ++m) {
    const bvh::PrimitiveBounds input = bvh::triangleBounds(meshes[m].view());
    const bvh::Bvh tree = traceScene.meshBvh().download(m);
    EXPECT_EQ(bvh::test::structuralProblem(tree, input.bounds, HMB_BVH_MAX_LEAF), "") << "mesh " << m;
    EXPECT_LE(bvh::sahCost(tree) / bvh::sahCost(bvh::buildReferenceSah(input.bounds, input.centroids)), kMaxSahRatio)
        << "mesh " << m;
  }
}

// A top level's shape on a CPU device (BvhBuildShape::forTopLevel) hands a tree of up to
// HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU primitives to one small task, with no level, built or
// recorded; the tree is sound and as cheap as the levels' (leaves of one, as instances have, and
// of up to four); one more primitive takes the levels.
TEST_F(DeviceBvh, ATopLevelShapeBuildsHundredsOfPrimitivesInOneSmallTask) {
  const passes::BvhBuildShape top{HMB_BVH_LEVEL_GROUP, true, HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU};
  EXPECT_EQ(top.describe(), "8 lanes, per-lane bins, small tasks of up to " +
                                std::to_string(HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU));
  EXPECT_EQ(passes::BvhBuildShape::forTopLevel(context()).smallTask, context().profile().topLevelSmallTask);
  EXPECT_EQ(passes::BvhBuildShape::forDevice(context()).smallTask, HMB_BVH_SMALL_TASK);
  for (const uint32_t n : {321u, HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU, HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU + 1u}) {
    const TriangleMesh mesh = bvh::test::randomSoup(n, 0.1f, 60 + n);
    const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh.view());
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "boxes");
    const glm::uvec2 root(0u, n);
    const bool oneTask = n <= HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU;
    const std::string what = std::to_string(n) + " primitives";
    for (const uint32_t maxLeaf : {HMB_BVH_MAX_INSTANCE_LEAF, HMB_BVH_MAX_LEAF}) {
      passes::BvhBuildPass builder(context(), "top level", maxLeaf, top);
      vk::FrameRecorder frame(context());
      const passes::BvhBuildStats& stats = builder.build(frame, buffer, n, std::span(&root, 1));
      EXPECT_EQ(stats.levelMilliseconds.empty(), oneTask) << what;
      if (oneTask) {
        EXPECT_EQ(stats.smallTasks, 1u) << what;
      }
      const bvh::Bvh built = builder.download(0);
      EXPECT_EQ(bvh::test::structuralProblem(built, input.bounds, maxLeaf), "") << what << ", leaves of " << maxLeaf;
      if (maxLeaf == HMB_BVH_MAX_LEAF) {
        EXPECT_LE(bvh::sahCost(built) / bvh::sahCost(bvh::buildReferenceSah(input.bounds, input.centroids)),
                  kMaxSahRatio)
            << what;
      }
      // Recorded into a frame, under the depth bound it records for.
      frame.begin();
      builder.record(frame, "top level", buffer, n, std::span(&root, 1));
      frame.submitAndWait();
      builder.readRecordedCounts();
      const bvh::Bvh recorded = builder.download(0);
      EXPECT_EQ(bvh::test::structuralProblem(recorded, input.bounds, maxLeaf), "") << what << ", recorded";
      EXPECT_LE(levelsBelowRoot(recorded), builder.recordedDepthBound(n)) << what;
    }
  }
}

// What a kept tree with insertions (passes::BvhBuildPass::recordKeptWithInsertions) must be:
// sound over every primitive (each in one leaf, every node bounding its children, as
// traversal unpacks them), the frame tree 0's root's, every node the host's packing of its
// exact node in it, the kept primitives' leaves all where the kept tree had them, and no node
// deeper than traversal's stack holds.
void expectInserted(const passes::BvhBuildPass& builder, std::span<const Aabb> boxes, const std::string& what) {
  const auto exact = builder.exactNodes().download<gpu::BvhNode>();
  const auto packed = builder.nodes().download<gpu::BvhPackedNode>();
  const gpu::BvhFrame frame = builder.frames().download<gpu::BvhFrame>().at(0);
  const gpu::BvhFrame expected = bvh::frameOf(bvh::boundsOf(exact.at(0)));
  EXPECT_EQ(frame.origin, expected.origin) << what;
  EXPECT_EQ(frame.step, expected.step) << what;
  for (std::vector<uint32_t> stack{0u}; !stack.empty();) {
    const uint32_t index = stack.back();
    stack.pop_back();
    const gpu::BvhNode node = exact.at(index);
    const gpu::BvhPackedNode want = bvh::packNode(node, expected), got = packed.at(index);
    ASSERT_TRUE(got.x == want.x && got.y == want.y && got.z == want.z && got.leftOrFirstCount == want.leftOrFirstCount)
        << what << ", node " << index;
    if (node.count == 0) stack.insert(stack.end(), {node.leftOrFirst, node.leftOrFirst + 1});
  }
  const bvh::Bvh tree = builder.download(0);
  EXPECT_EQ(bvh::test::structuralProblem(tree, boxes, HMB_BVH_MAX_INSTANCE_LEAF), "") << what;
  EXPECT_LE(levelsBelowRoot(tree), HMB_BVH_MAX_DEPTH) << what;
}

// A top level whose still instances' tree is kept and whose moving ones are inserted into it
// (passes::BvhBuildPass::recordKeptWithInsertions), in both shapes (the kept tree one small
// task, the CPU top level's; or split in levels): sound, packed as the host packs, its SAH
// cost near a build over all. Inserted again from moved boxes (recordInsertionsAgain), the
// kept tree's exact nodes are restored as they were built, and the moved ones are in.
TEST_F(DeviceBvh, AKeptTreeTakesInsertionsAndTakesThemAgainFromMovedBoxes) {
  const uint32_t n = 300, kept = n - HMB_BVH_MAX_INSERTED;
  std::vector<uint32_t> order(n);
  for (uint32_t i = 0; i < n; ++i) order[i] = (i * 7u + 3u) % n;  // kept and inserted primitives interleave
  const std::vector<Aabb> boxes = bvh::triangleBounds(bvh::test::randomSoup(n, 0.1f, 72).view()).bounds;
  std::vector<Aabb> moved = boxes;
  const std::vector<Aabb> elsewhere = bvh::triangleBounds(bvh::test::randomSoup(n, 0.1f, 73).view()).bounds;
  for (uint32_t k = kept; k < n; ++k) moved[order[k]] = {elsewhere[k].min * 1.5f, elsewhere[k].max * 1.5f};
  const passes::BvhBuildShape shapes[] = {{HMB_BVH_LEVEL_GROUP, true, HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU}, {}};
  for (const passes::BvhBuildShape& shape : shapes) {
    const std::string what = shape.describe();
    passes::BvhBuildPass builder(context(), "kept", HMB_BVH_MAX_INSTANCE_LEAF, shape);
    const vk::Buffer first = vk::uploadedBuffer(context(), passes::bvhBoxes(boxes), "boxes");
    vk::FrameRecorder frame(context());
    frame.begin();
    builder.recordKeptWithInsertions(frame, "kept", first, order, kept);
    frame.submitAndWait();
    builder.readRecordedCounts();
    ASSERT_TRUE(builder.hasInsertions());
    expectInserted(builder, boxes, what + ", first insertions");
    std::vector<glm::vec3> centres;
    for (const Aabb& box : boxes) centres.push_back(box.center());
    const double ratio = bvh::sahCost(builder.download(0)) / bvh::sahCost(bvh::buildReferenceSah(boxes, centres));
    std::printf("[ device   ] %s: %u kept, %u inserted: SAH %.3fx the full sweep's over all\n", what.c_str(), kept, n - kept,
                ratio);
    EXPECT_LE(ratio, 1.3) << what;

    const vk::Buffer second = vk::uploadedBuffer(context(), passes::bvhBoxes(moved), "moved boxes");
    frame.begin();
    builder.recordInsertionsAgain(frame, "kept", second);
    frame.submitAndWait();
    builder.readRecordedCounts();
    expectInserted(builder, moved, what + ", inserted again");
    EXPECT_THROW(builder.compact(frame), Error) << what;
  }
}

// Triangles along the x axis, flat in z, each `ratio` times as far out and as large as the one
// before from `first` on, then `cluster` tiny ones near the first: the SAH peels the chain's
// largest off level after level, each level binning the cluster again.
TriangleMesh peeledChain(uint32_t chain, double ratio, double first, uint32_t cluster) {
  TriangleMesh mesh;
  double x = first;
  for (uint32_t i = 0; i < chain; ++i, x *= ratio) {
    const auto w = static_cast<float>(0.1 * x);
    const glm::vec3 corner(static_cast<float>(x), 0.0f, 0.0f);
    mesh.addTriangle(corner, corner + glm::vec3(w, 0.0f, 0.0f), corner + glm::vec3(0.0f, w, 0.0f), 1);
  }
  const TriangleMesh soup = bvh::test::randomSoup(cluster, 0.1f, 5);
  for (uint32_t t = 0; t < soup.triangleCount(); ++t) {
    glm::vec3 v[3];
    for (int k = 0; k < 3; ++k)
      v[k] = soup.positions[soup.indices[3 * t + k]] * static_cast<float>(first) + glm::vec3(first, 0.0, 0.0);
    mesh.addTriangle(v[0], v[1], v[2], 1);
  }
  return mesh;
}

// One invocation builds a CPU top level of up to HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU instances,
// and lavapipe ends an invocation's loops silently after 65535 iterations in all. Deep trees
// of 512 (a chain spanning 31 decades, flat in z; a chain of 64 peeled off a cluster of 448)
// are built whole, waited and recorded, within the depth bound that budget sets
// (smallTaskDepthBound), their nodes packed after the task. Where the task packed its own
// nodes and took no such bound, both came back unfinished. A driver without a budget
// (vk::DeviceProfile::loopBudget empty, Mesa 25) builds them whole, as deep as they come.
TEST_F(DeviceBvh, AOneInvocationTopLevelStaysWithinLavapipesLoopBudget) {
  const std::optional<uint32_t> budget = HMB_LOOP_BUDGET;
  EXPECT_EQ(passes::BvhBuildPass::smallTaskDepthBound(HMB_BVH_SMALL_TASK, false, budget), HMB_BVH_MAX_DEPTH);
  const uint32_t n = HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU;
  const uint32_t bound = passes::BvhBuildPass::smallTaskDepthBound(n, true, budget);
  EXPECT_LT(bound, HMB_BVH_MAX_DEPTH);
  EXPECT_LT(passes::BvhBuildPass::smallTaskDepthBound(n, false, budget), bound);
  // A driver without a budget leaves every tree its 64 levels.
  EXPECT_EQ(passes::BvhBuildPass::smallTaskDepthBound(n, false, std::nullopt), HMB_BVH_MAX_DEPTH);
  const std::optional<uint32_t> driverBudget = context().profile().loopBudget;
  const uint32_t deviceBound = passes::BvhBuildPass::smallTaskDepthBound(n, true, driverBudget);
  const passes::BvhBuildShape top{HMB_BVH_LEVEL_GROUP, true, n};
  ASSERT_TRUE(top.packsLater());
  const std::pair<const char*, TriangleMesh> cases[] = {{"a chain of 512", peeledChain(n, 1.15, 1e-15, 0)},
                                                        {"64 peeled off 448", peeledChain(64, 3.0, 1e-14, n - 64)}};
  for (const auto& [what, mesh] : cases) {
    const bvh::PrimitiveBounds input = bvh::triangleBounds(mesh.view());
    ASSERT_EQ(input.bounds.size(), n);
    const vk::Buffer buffer = vk::uploadedBuffer(context(), passes::bvhBoxes(input.bounds), "boxes");
    const glm::uvec2 root(0u, n);
    passes::BvhBuildPass levels(context(), "levels", HMB_BVH_MAX_INSTANCE_LEAF, binned());
    vk::FrameRecorder frame(context());
    levels.build(frame, buffer, n, std::span(&root, 1));
    if (driverBudget)
      EXPECT_GT(levelsBelowRoot(levels.download(0)), bound) << what << ": deeper than the bound where unbounded";
    passes::BvhBuildPass builder(context(), "top level", HMB_BVH_MAX_INSTANCE_LEAF, top);
    EXPECT_EQ(builder.depthBound(n), deviceBound);
    const passes::BvhBuildStats stats = builder.build(frame, buffer, n, std::span(&root, 1));
    EXPECT_EQ(stats.smallTasks, 1u) << what;
    EXPECT_EQ(stats.leaves, n) << what;
    const bvh::Bvh built = builder.download(0);
    EXPECT_EQ(bvh::test::structuralProblem(built, input.bounds, HMB_BVH_MAX_INSTANCE_LEAF), "") << what;
    EXPECT_LE(levelsBelowRoot(built), deviceBound) << what;
    frame.begin();
    builder.record(frame, "top level", buffer, n, std::span(&root, 1));
    frame.submitAndWait();
    EXPECT_EQ(builder.readRecordedCounts().leaves, n) << what << ", recorded";
    const bvh::Bvh recorded = builder.download(0);
    EXPECT_EQ(bvh::test::structuralProblem(recorded, input.bounds, HMB_BVH_MAX_INSTANCE_LEAF), "") << what;
    std::printf("[ budget   ] %s: %u levels below the root unbounded, %u under the bound of %u\n", what,
                levelsBelowRoot(levels.download(0)), levelsBelowRoot(built), deviceBound);
  }
}

TEST_F(DeviceBvh, ManyMeshesBuildTogether) {
  scene::Scene scene;
  std::vector<TriangleMesh> meshes = {bvh::test::randomSoup(300, 0.05f, 5), bvh::test::grid(12, 6),
                                      bvh::test::randomSoup(1, 0.1f, 7), bvh::test::cubeSphere(6)};
  for (const TriangleMesh& mesh : meshes) {
    scene::Mesh m;
    m.positions = mesh.positions;
    m.indices = mesh.indices;
    scene.meshes.push_back(m);
  }
  scene.meshes.push_back({});  // a mesh without triangles
  vk::FrameRecorder frame(context());
  const TraceScene traceScene(context(), scene, frame);
  for (uint32_t m = 0; m < meshes.size(); ++m) {
    const bvh::PrimitiveBounds input = bvh::triangleBounds(meshes[m].view());
    const bvh::Bvh tree = traceScene.meshBvh().download(m);
    EXPECT_EQ(bvh::test::structuralProblem(tree, input.bounds, HMB_BVH_MAX_LEAF), "") << "mesh " << m;
    EXPECT_LE(levelsBelowRoot(tree), HMB_BVH_MAX_DEPTH) << "mesh " << m;
  }
  EXPECT_TRUE(traceScene.meshBvh().download(4).nodes.empty());
}

TEST_F(DeviceBvh, SahCostWithinBoundOfFullSweepOnReferenceScenes) {
  for (const std::string& name : scene::referenceSceneNames()) {
    const scene::Scene scene = scene::makeReferenceScene(name);
    const TriangleMesh mesh = bvh::test::sceneTriangles(scene, scene.settings.frameTime);
    EXPECT_LE(checkBuild(mesh, name), maxSahRatio()) << name;
  }
}

TEST_F(DeviceBvh, SahCostWithinBoundOfFullSweepOnAMillionTriangles) {
  const TriangleMesh mesh = bvh::test::cubeSphere(290);  // 6 * 290^2 * 2 = 1,009,200 triangles
  ASSERT_GE(mesh.triangleCount(), 1000000u);
  EXPECT_LE(checkBuild(mesh, "cube sphere"), maxSahRatio());
}


}  // namespace
}  // namespace hmb::trace::test
