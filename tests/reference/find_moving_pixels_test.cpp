// find_moving_pixels.comp by hand: a camera looking down -z at a box that covers the left half
// of its view, among boxes it never sees, lists exactly the left half; past the boxes one
// invocation may test (HMB_MOVING_PIXELS_MAX_BOXES, llvmpipe's loop budget) every pixel is
// listed, so none that a moving instance crosses is sampled once.
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "kernels/manifest.h"
#include "kernels/reference/reference_layout.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

constexpr uint32_t kWidth = 16, kHeight = 8;

// The listed pixels, sorted, for `boxes` (lower, upper per box) seen from the origin down -z.
std::vector<uint32_t> movingPixels(vk::Context& context, const std::vector<glm::vec4>& boxes) {
  const gpu::PinholeCamera camera{glm::vec4(0.0f, 0.0f, 0.0f, 1.0f), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f),
                                  glm::vec4(0.0f, -1.0f, 0.0f, 0.0f), glm::vec4(0.0f, 0.0f, -1.0f, 0.0f)};
  const vk::Buffer cameras = vk::uploadedBuffer(context, std::vector<gpu::PinholeCamera>{camera}, "test camera");
  const vk::Buffer boxBuffer = vk::uploadedBuffer(context, boxes, "test boxes");
  const vk::Buffer counter = vk::uploadedBuffer(context, std::vector<uint32_t>{0u}, "test counter");
  const vk::Buffer list(context, kWidth * kHeight * sizeof(uint32_t), vk::MemoryUse::Device, "test list");
  const vk::ComputeKernel kernel(context, kernels::kernel("reference/find_moving_pixels"));
  vk::FrameRecorder frame(context);
  frame.begin();
  frame.dispatch("find-moving-pixels", kernel,
                 {{HMB_MOVING_PIXELS_BINDING_CAMERAS, &cameras},
                  {HMB_MOVING_PIXELS_BINDING_BOXES, &boxBuffer},
                  {HMB_MOVING_PIXELS_BINDING_COUNTER, &counter},
                  {HMB_MOVING_PIXELS_BINDING_LIST, &list}},
                 gpu::MovingPixelsParams{kWidth, kHeight, uint32_t(boxes.size() / 2), 0u, 0.0f, 1e30f, 0u, 0u},
                 {vk::groupsFor(kWidth, HMB_MOVING_PIXELS_GROUP_X), vk::groupsFor(kHeight, HMB_MOVING_PIXELS_GROUP_Y), 1});
  frame.submitAndWait();
  const uint32_t count = counter.download<uint32_t>().at(0);
  EXPECT_LE(count, kWidth * kHeight);
  std::vector<uint32_t> out = list.download<uint32_t>();
  out.resize(std::min(count, kWidth * kHeight));
  std::sort(out.begin(), out.end());
  return out;
}

// `unseen` boxes behind the camera, then one over x <= 0 between depths 5 and 10: the rays of
// the left half (ndc x < 0, at least 0.3 units left of the box's side there) meet it.
std::vector<glm::vec4> boxesWithTheSeenOneLast(uint32_t unseen) {
  std::vector<glm::vec4> boxes;
  for (uint32_t i = 0; i < unseen; ++i) {
    boxes.emplace_back(-1.0f + float(i % 7), -1.0f, 5.0f + float(i % 13), 0.0f);
    boxes.emplace_back(1.0f + float(i % 7), 1.0f, 6.0f + float(i % 13), 0.0f);
  }
  boxes.emplace_back(-100.0f, -100.0f, -10.0f, 0.0f);
  boxes.emplace_back(0.0f, 100.0f, -5.0f, 0.0f);
  return boxes;
}

std::vector<uint32_t> leftHalf() {
  std::vector<uint32_t> out;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth / 2; ++x) out.push_back(y * kWidth + x);
  return out;
}

using FindMovingPixelsTest = VulkanTest;

TEST_F(FindMovingPixelsTest, ThePixelsWhoseRayMeetsAMovingBoxByHand) {
  EXPECT_EQ(movingPixels(context(), boxesWithTheSeenOneLast(0)), leftHalf());
  EXPECT_EQ(movingPixels(context(), boxesWithTheSeenOneLast(7)), leftHalf());
  std::vector<glm::vec4> unseen = boxesWithTheSeenOneLast(7);
  unseen.resize(14);
  EXPECT_TRUE(movingPixels(context(), unseen).empty()) << "the unseen boxes alone list nothing";
}

// The seen box last, after as many unseen ones as an invocation tests in all: exactly the left
// half. One more, past the 65535 loop rounds llvmpipe 22.3 allows an invocation (which never
// reached the seen box there and listed nothing): every pixel, untested.
TEST_F(FindMovingPixelsTest, MoreBoxesThanAnInvocationTestsListEveryPixel) {
  EXPECT_EQ(movingPixels(context(), boxesWithTheSeenOneLast(HMB_MOVING_PIXELS_MAX_BOXES - 1)), leftHalf());
  const std::vector<uint32_t> all = movingPixels(context(), boxesWithTheSeenOneLast(70000));
  EXPECT_EQ(all.size(), size_t(kWidth) * kHeight);
  for (size_t i = 0; i < all.size(); ++i) EXPECT_EQ(all[i], uint32_t(i));
}

}  // namespace
}  // namespace hmb::test
