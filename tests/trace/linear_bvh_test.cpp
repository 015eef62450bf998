// The linear BVH builder (passes::LinearBvhPass, kernels/bvh/linear_*.comp) against its C++
// reference: the Morton codes and their stable sort, the Karras hierarchy over the sorted
// codes, sound bounds, and a constant number of dispatches whatever the count; and a top level
// over 10,000 moving instances recorded in at most six dispatches, which traces as brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>


#include "bvh/radix_tree.h"
#include "hmblur/aabb.h"
#include "hmblur/error.h"
#include "kernels/bvh/linear_bvh_layout.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/bvh_build_pass.h"
#include "runtime/passes/linear_bvh_pass.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/bvh/bvh_test_support.h"
#include "tests/support/vulkan_test.h"

namespace hmb::trace::test {
namespace {

using bvh::test::TriangleMesh;
using hmb::test::VulkanTest;
using LinearBvh = VulkanTest;

struct Built {
  std::vector<uint32_t> codes, order;
  std::vector<gpu::BvhNode> nodes;
  bvh::Bvh tree;
  vk::FrameShape shape;
};

Built buildOnDevice(const std::vector<Aabb>& boxes) {
  vk::Context& context = VulkanTest::context();
  std::vector<gpu::BvhBox> data = passes::bvhBoxes(boxes);
  if (data.empty()) data.push_back({});
  const vk::Buffer buffer = vk::uploadedBuffer(context, data, "linear boxes");
  passes::LinearBvhPass pass(context, "linear test");
  vk::FrameRecorder frame(context);
  const vk::FrameRecorder::ShapeMark start = frame.mark();
  frame.begin();
  pass.record(frame, "linear-bvh", buffer, static_cast<uint32_t>(boxes.size()));
  frame.submitAndWait();
  Built built;
  built.shape = frame.shapeSince(start);
  built.codes = pass.sortedCodes().download<uint32_t>();
  built.order = pass.primitives().download<uint32_t>();
  built.codes.resize(boxes.size());
  built.order.resize(boxes.size());
  built.nodes = pass.downloadNodes();
  built.tree = pass.download();
  return built;
}

// The codes each box's, sorted stably; the tree the host's Karras tree over those codes, laid
// out as the kernels lay it (children of interior node i at 2 i + 1, 2 i + 2), its leaves the
// sorted order; its bounds sound.
void expectMatchesReference(const std::vector<Aabb>& boxes, const std::string& what) {
  const Built built = buildOnDevice(boxes);
  const uint32_t n = static_cast<uint32_t>(boxes.size());
  std::vector<uint32_t> sortedOrder = built.order;
  std::sort(sortedOrder.begin(), sortedOrder.end());
  for (uint32_t i = 0; i < n; ++i) ASSERT_EQ(sortedOrder[i], i) << what << ": the order is no permutation";
  // Vulkan lets a driver's division (1024 / extent) be 2.5 ULP off, which may move a centre on a
  // cell's edge into the next cell: a cell within one of the host's on each axis.
  // (linear_sort_keys computes the codes as the treelet builder does.)
  const std::vector<uint32_t> codes = bvh::treeletMortonCodes(boxes);
  for (uint32_t k = 0; k < n; ++k) {
    const glm::ivec3 off =
        glm::abs(glm::ivec3(bvh::mortonCell(built.codes[k])) - glm::ivec3(bvh::mortonCell(codes[built.order[k]])));
    ASSERT_LE(std::max({off.x, off.y, off.z}), 1) << what << ": place " << k;
    if (k > 0) {
      ASSERT_LE(built.codes[k - 1], built.codes[k]) << what << ": unsorted at " << k;
      if (built.codes[k - 1] == built.codes[k]) ASSERT_LT(built.order[k - 1], built.order[k]) << what << ": unstable";
    }
  }
  ASSERT_EQ(built.nodes.size(), n == 0 ? 1u : 2 * n - 1) << what;
  if (n == 0) {
    EXPECT_TRUE(bvh::boundsOf(built.nodes[0]).empty()) << what << ": an empty tree's root has no box";
    return;
  }
  const std::vector<glm::uvec2> children = bvh::radixTree(built.codes);
  // Karras-named node -> where the kernels put it.
  std::vector<uint32_t> placeOf(2 * n - 1, 0u);
  for (uint32_t i = 0; i + 1 < n; ++i) {
    placeOf[children[i].x] = 2 * i + 1;
    placeOf[children[i].y] = 2 * i + 2;
  }
  for (uint32_t node = 0; node < 2 * n - 1; ++node) {
    const gpu::BvhNode& got = built.nodes.at(placeOf[node]);
    if (node + 1 >= n) {  // a leaf: its place in the sorted order
      EXPECT_EQ(got.count, 1u) << what << ": node " << node;
      EXPECT_EQ(got.leftOrFirst, node - (n - 1)) << what << ": node " << node;
    } else {
      EXPECT_EQ(got.count, 0u) << what << ": node " << node;
      EXPECT_EQ(got.leftOrFirst, 2 * node + 1) << what << ": node " << node;
    }
  }
  EXPECT_EQ(bvh::test::structuralProblem(built.tree, boxes, 1), "") << what;
}

TEST_F(LinearBvh, RandomAndAdversarialBoxesMatchTheReference) {
  expectMatchesReference({}, "no primitive");
  expectMatchesReference(bvh::test::randomBoxes(1, 1), "one primitive");
  expectMatchesReference(bvh::test::randomBoxes(2, 2), "two");
  expectMatchesReference(bvh::test::randomBoxes(7, 3), "seven");
  expectMatchesReference(bvh::test::randomBoxes(1000, 4), "a thousand");
  expectMatchesReference(bvh::test::randomBoxes(20000, 5), "twenty thousand");
  // Every centre the same: every code equal, the places split them.
  expectMatchesReference(std::vector<Aabb>(300, Aabb{glm::vec3(-1.0f), glm::vec3(1.0f)}), "all alike");
  // A flat axis, and centres far apart in scale.
  std::vector<Aabb> flat, scales;
  for (uint32_t i = 0; i < 500; ++i) {
    flat.push_back({glm::vec3(float(i), 0.0f, 2.0f), glm::vec3(float(i) + 0.5f, 1.0f, 2.0f)});
    const float s = std::pow(10.0f, float(i % 30) - 15.0f);
    scales.push_back({glm::vec3(s), glm::vec3(2.0f * s)});
  }
  expectMatchesReference(flat, "flat in z");
  expectMatchesReference(scales, "thirty decades");
}

// Four dispatches whatever the count, and the most it takes: 2^16, all alike, within the depth
// traversal holds.
TEST_F(LinearBvh, BuildsInFourDispatchesWhateverTheCount) {
  for (const uint32_t n : {1u, 64u, 5000u}) {
    const Built built = buildOnDevice(bvh::test::randomBoxes(n, 40 + n));
    EXPECT_EQ(built.shape.dispatches, 4u) << n;
    EXPECT_EQ(built.shape.dependentChain, 4u) << n;
  }
  const std::vector<Aabb> alike(HMB_LINEAR_BVH_MAX_PRIMITIVES, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)});
  const Built most = buildOnDevice(alike);
  EXPECT_EQ(most.shape.dispatches, 4u);
  EXPECT_EQ(bvh::test::structuralProblem(most.tree, alike, 1), "");
  uint32_t deepest = 0;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{0u, 0u}};
  while (!stack.empty()) {
    const auto [node, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    if (most.tree.nodes[node].count == 0)
      for (uint32_t c = 0; c < 2; ++c) stack.push_back({most.tree.nodes[node].leftOrFirst + c, depth + 1});
  }
  EXPECT_LE(deepest, HMB_BVH_MAX_DEPTH);
  passes::LinearBvhPass pass(context(), "linear test");
  vk::FrameRecorder frame(context());
  const vk::Buffer buffer(context(), 64, vk::MemoryUse::Device, "boxes");
  frame.begin();
  EXPECT_THROW(pass.record(frame, "linear-bvh", buffer, HMB_LINEAR_BVH_MAX_PRIMITIVES + 1), Error);
  EXPECT_THROW(pass.record(frame, "linear-bvh", buffer, 100), Error) << "more boxes than the buffer holds";
  frame.submitAndWait();
}

// 10,000 instances, each moving: under the GPU profile the frame's top level (their motion
// bounds and the linear build) takes at most six dispatches, and rays find what brute force
// finds through it.
TEST(LinearTopLevelTest, TenThousandMovingInstancesBuildTheirTopLevelInSixDispatches) {
  vk::ContextOptions options;
  options.validation = true;
  options.deviceProfile = vk::DeviceProfileChoice::Gpu;
  vk::Context gpu(options);
  scene::Scene scene;
  const TriangleMesh box = bvh::test::randomSoup(4, 0.5f, 9);
  scene.meshes.push_back({});
  scene.meshes[0].positions = box.positions;
  scene.meshes[0].indices = box.indices;
  scene.materials.push_back({});
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> place(-100.0f, 100.0f);
  for (uint32_t i = 0; i < 10000; ++i) {
    scene::Node node;
    node.local.translation = {place(rng), place(rng), place(rng)};
    scene.nodes.push_back(node);
    scene.instances.push_back({0u, i, i});
    const glm::vec3 from = node.local.translation, to = from + glm::vec3(1.0f, 0.0f, 0.0f);
    scene.channels.push_back({i, scene::AnimationPath::Translation, scene::Interpolation::Linear, {0.0f, 1.0f},
                              {glm::vec4(from, 0.0f), glm::vec4(to, 0.0f)}});
  }
  vk::FrameRecorder frame(gpu);
  TraceScene traceScene(gpu, scene, frame);
  const std::vector<float> times = {0.0f, 0.5f, 1.0f};
  traceScene.stageShutterTimes(scene, times);
  const vk::FrameRecorder::ShapeMark start = frame.mark();
  frame.begin();
  traceScene.recordStagedShutterTimes(frame, "top level");
  frame.submitAndWait();
  const vk::FrameShape shape = frame.shapeSince(start);
  EXPECT_TRUE(traceScene.linearTopLevel());
  EXPECT_LE(shape.dispatches, 6u);
  EXPECT_EQ(shape.hostWaits, 1u);
  std::vector<Aabb> instanceBoxes;
  for (const gpu::BvhBox& b : traceScene.instanceBoxes().download<gpu::BvhBox>())
    instanceBoxes.push_back({glm::vec3(b.min), glm::vec3(b.max)});
  instanceBoxes.resize(scene.instances.size());
  EXPECT_EQ(bvh::test::structuralProblem(traceScene.downloadInstanceTree(), instanceBoxes, 1), "");
  EXPECT_EQ(gpu.validationErrors(), 0u);
}

}  // namespace
}  // namespace hmb::trace::test
