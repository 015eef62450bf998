#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "kernels/debug/test_pattern.h"
#include "kernels/manifest.h"
#include "runtime/passes/test_pattern_pass.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using FrameRecorderTest = VulkanTest;

// Plain C++ reference of kernels/debug/test_pattern.comp.
glm::vec4 testPatternPixel(uint32_t x, uint32_t y, uint32_t width, uint32_t height, float time) {
  const glm::vec2 size(width, height);
  const glm::vec2 centre = glm::vec2(x, y) + 0.5f;
  const glm::vec2 uv = centre / size;
  const uint32_t cx = x / HMB_TEST_PATTERN_CHECKER, cy = y / HMB_TEST_PATTERN_CHECKER;
  glm::vec4 colour(uv.x, uv.y, ((cx + cy) & 1u) == 0 ? 0.25f : 0.75f, 1.0f);
  const glm::vec2 disc(glm::fract(time) * size.x, 0.5f * size.y);
  const float radius = 0.25f * std::min(size.x, size.y);
  const glm::vec2 d = centre - disc;
  if (glm::dot(d, d) <= radius * radius) colour = glm::vec4(1.0f);
  return colour;
}

std::vector<glm::vec4> renderTestPattern(vk::FrameRecorder& frame, uint32_t width, uint32_t height, float time,
                                         vk::FrameTimings* timings = nullptr) {
  vk::Buffer image(VulkanTest::context(), uint64_t(width) * height * sizeof(glm::vec4), vk::MemoryUse::Device, "image");
  passes::TestPatternPass pass(VulkanTest::context());
  frame.begin();
  pass.record(frame, image, width, height, time);
  const vk::FrameTimings t = frame.submitAndWait();
  if (timings) *timings = t;
  return image.download<glm::vec4>();
}

TEST_F(FrameRecorderTest, TestPatternMatchesItsReferenceAtOddSizes) {
  vk::FrameRecorder frame(context());
  for (const auto& [width, height] : {std::pair{1u, 1u}, {7u, 3u}, {130u, 67u}}) {
    const float time = 0.37f;
    const auto pixels = renderTestPattern(frame, width, height, time);
    ASSERT_EQ(pixels.size(), size_t(width) * height);
    for (uint32_t y = 0; y < height; ++y)
      for (uint32_t x = 0; x < width; ++x) {
        const glm::vec4 expected = testPatternPixel(x, y, width, height, time);
        const glm::vec4 got = pixels[y * width + x];
        for (int c = 0; c < 4; ++c) ASSERT_NEAR(got[c], expected[c], 1e-6f) << x << "," << y << " c" << c;
      }
  }
}

TEST_F(FrameRecorderTest, EveryPassGetsAFiniteNonNegativeTime) {
  if (!context().info().timestamps) GTEST_SKIP() << "device has no timestamps";
  vk::FrameRecorder frame(context());
  vk::Buffer a(context(), 4096, vk::MemoryUse::Device, "a");
  vk::Buffer image(context(), 64 * 64 * sizeof(glm::vec4), vk::MemoryUse::Device, "image");
  passes::TestPatternPass pattern(context());
  frame.begin();
  frame.fill("clear", a, 0x12345678u);
  pattern.record(frame, image, 64, 64, 0.0f);
  const vk::FrameTimings timings = frame.submitAndWait();
  ASSERT_EQ(timings.passes.size(), 2u);
  EXPECT_EQ(timings.passes[0].name, "clear");
  EXPECT_EQ(timings.passes[1].name, passes::TestPatternPass::kName);
  for (const auto& pass : timings.passes) {
    ASSERT_TRUE(pass.milliseconds.has_value()) << pass.name;
    EXPECT_TRUE(std::isfinite(*pass.milliseconds) && *pass.milliseconds >= 0.0) << pass.name;
  }
  ASSERT_TRUE(timings.frameMilliseconds.has_value());
  // Each pass runs from the end of the one before: together they are the frame.
  EXPECT_NEAR(*timings.passes[0].milliseconds + *timings.passes[1].milliseconds, *timings.frameMilliseconds,
              1e-6 * (1.0 + *timings.frameMilliseconds));
  for (uint32_t word : a.download<uint32_t>()) ASSERT_EQ(word, 0x12345678u);
}

TEST_F(FrameRecorderTest, RecorderIsReusableAcrossFrames) {
  vk::FrameRecorder frame(context());
  const auto first = renderTestPattern(frame, 16, 16, 0.1f);
  const auto second = renderTestPattern(frame, 16, 16, 0.6f);
  EXPECT_NE(first, second);  // the disc moved
  EXPECT_EQ(renderTestPattern(frame, 16, 16, 0.1f), first);
}

TEST_F(FrameRecorderTest, MisuseIsAClearError) {
  vk::FrameRecorder frame(context());
  vk::ComputeKernel kernel(context(), kernels::kernel("debug/test_pattern"));
  vk::Buffer image(context(), 64, vk::MemoryUse::Device, "image");
  const gpu::TestPatternParams params{1, 1, 0.0f, 0};
  const vk::Binding linear{HMB_TEST_PATTERN_BINDING_LINEAR, &image};
  EXPECT_THROW(frame.dispatch("outside", kernel, {linear}, params, {1, 1, 1}), Error);
  frame.begin();
  EXPECT_THROW(frame.dispatch("two buffers", kernel, {linear, {HMB_TEST_PATTERN_BINDING_LINEAR + 1, &image}}, params,
                              {1, 1, 1}),
               Error);
  EXPECT_THROW(frame.dispatch("wrong push size", kernel, {linear}, uint32_t(0), {1, 1, 1}), Error);
  const uint32_t tooMany = context().limits().maxComputeWorkGroupCount[0] + 1;
  if (tooMany != 0) {
    EXPECT_THROW(frame.dispatch("too many groups", kernel, {linear}, params, {tooMany, 1, 1}), Error);
  }
  frame.submitAndWait();
}

// A frame's shape is counted as it is recorded: every dispatch (an empty one is not recorded),
// the indirect ones apart, transfers, the barrier after each pass and the one before the host
// reads, the submission and its wait, and the chain of dispatches each waiting on the one before.
TEST_F(FrameRecorderTest, CountsTheFramesShape) {
  vk::FrameRecorder frame(context());
  vk::Buffer image(context(), 16 * 16 * sizeof(glm::vec4), vk::MemoryUse::Device, "image");
  vk::Buffer a(context(), 4096, vk::MemoryUse::Device, "a");
  passes::TestPatternPass pattern(context());
  const vk::FrameRecorder::ShapeMark start = frame.mark();
  frame.begin();
  frame.fill("clear", a, 0u);
  pattern.record(frame, image, 16, 16, 0.0f);
  pattern.record(frame, image, 16, 16, 0.5f);
  frame.submitAndWait();
  const vk::FrameShape one = frame.shapeSince(start);
  EXPECT_EQ(one.dispatches, 2u);
  EXPECT_EQ(one.indirectDispatches, 0u);
  EXPECT_EQ(one.transfers, 1u);
  EXPECT_EQ(one.barriers, 4u);  // one a pass, one for the host
  EXPECT_EQ(one.submissions, 1u);
  EXPECT_EQ(one.hostWaits, 1u);
  EXPECT_EQ(one.dependentChain, 2u);
  // A read-back after the frame is not the frame's; a second submission, and the read-back
  // between the two, are.
  (void)a.download<uint32_t>();
  EXPECT_EQ(frame.shapeSince(start), one);
  const vk::FrameRecorder::ShapeMark second = frame.mark();
  frame.begin();
  pattern.record(frame, image, 16, 16, 0.0f);
  frame.submitAndWait();
  (void)a.download<uint32_t>();
  frame.begin();
  pattern.record(frame, image, 16, 16, 0.0f);
  frame.submitAndWait();
  const vk::FrameShape two = frame.shapeSince(second);
  EXPECT_EQ(two.dispatches, 2u);
  EXPECT_EQ(two.submissions, 2u);
  EXPECT_GE(two.hostWaits, 3u);  // two submissions and the read-back (through staging: its wait too)
  EXPECT_EQ(two.dependentChain, 2u);
  // Recorded into someone else's command buffer: no submission and no wait of the library's.
  const vk::FrameRecorder::ShapeMark engine = frame.mark();
  context().submitAndWait([&](VkCommandBuffer commandBuffer) {
    frame.beginInto(commandBuffer);
    pattern.record(frame, image, 16, 16, 0.0f);
    frame.endInto();
  });
  const vk::FrameShape recorded = frame.shapeSince(engine);
  EXPECT_EQ(recorded.dispatches, 1u);
  EXPECT_EQ(recorded.barriers, 3u);  // before the passes, after the pass, after the frame
  EXPECT_EQ(recorded.submissions, 0u);
  EXPECT_EQ(recorded.hostWaits, 0u);
  EXPECT_EQ(recorded.dependentChain, 1u);
}

}  // namespace
}  // namespace hmb::test
