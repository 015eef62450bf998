// The rasterizer's setup and pair buffers are sized by estimate: a frame that needs more must
// flag the overflow, rasterize nothing half-way, and after growIfOverflowed() render exactly
// what a pass with room to spare renders.
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "kernels/raster/raster_layout.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/raster/raster_harness.h"
#include "tests/raster/raster_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using CapacityTest = VulkanTest;

// Thousands of overlapping triangles, each touching several tiles, at random depths.
ClipTriangles crowd(uint32_t count) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> xy(-1.2f, 1.2f), z(0.05f, 0.95f);
  ClipTriangles t;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec2 c(xy(rng), xy(rng));
    const float depth = z(rng);
    t.add({c.x - 0.6f, c.y - 0.5f, depth, 1.0f}, {c.x + 0.6f, c.y - 0.4f, depth, 1.0f}, {c.x, c.y + 0.6f, depth, 1.0f});
  }
  return t;
}

// The triangles on the device, every one double-sided, as RasterInputs.
struct UploadedTriangles {
  vk::Buffer clip, triangles, instances;
  UploadedTriangles(const vk::Context& context, const ClipTriangles& input)
      : clip(vk::uploadedBuffer(context, input.clip, "clip")),
        triangles(vk::uploadedBuffer(context, input.triangles, "triangles")),
        instances(vk::uploadedBuffer(context, doubleSided(input.doubleSided.size()), "instances")) {}
  static std::vector<gpu::GpuInstance> doubleSided(size_t count) {
    std::vector<gpu::GpuInstance> instances(count);
    for (auto& instance : instances) instance.flags = HMB_INSTANCE_DOUBLE_SIDED;
    return instances;
  }
  passes::RasterInputs inputs(size_t count) const {
    return {&triangles, &instances, &clip, static_cast<uint32_t>(count)};
  }
};

TEST_F(CapacityTest, OverflowGrowsTheBuffersAndTheSecondFrameMatchesARoomyPass) {
  constexpr uint32_t kWidth = 64, kHeight = 48;
  const ClipTriangles input = crowd(3000);
  for (auto scheme : {passes::VisibilityScheme::Int64Atomics, passes::VisibilityScheme::Depth32TwoPass,
                       passes::VisibilityScheme::TileLists}) {
    SCOPED_TRACE(passes::visibilitySchemeName(scheme));
    const UploadedTriangles uploaded(context(), input);
    const passes::RasterInputs inputs = uploaded.inputs(input.triangles.size());
    vk::Buffer visibility(context(), passes::RasterizePass::visibilityBytes(kWidth, kHeight), vk::MemoryUse::Device,
                          "visibility");

    // Reserved for one triangle: both the setup and the pair capacity overflow.
    passes::RasterizePass pass(context(), scheme);
    pass.reserve(1, kWidth, kHeight);
    const uint32_t setupBefore = pass.setupCapacity(), pairsBefore = pass.pairCapacity();
    vk::FrameRecorder frame(context());
    frame.begin();
    pass.record(frame, inputs, visibility, kWidth, kHeight);
    frame.submitAndWait();
    // Nothing is rasterized from an overflowing frame (no half-drawn picture).
    for (const glm::uvec2& e : visibility.download<glm::uvec2>()) ASSERT_EQ(e.x, HMB_VIS_EMPTY);
    ASSERT_TRUE(pass.growIfOverflowed());
    EXPECT_GT(pass.setupCapacity(), setupBefore);
    EXPECT_GT(pass.pairCapacity(), pairsBefore);
    EXPECT_EQ(pass.stats().regrowths, 1u);

    frame.begin();
    pass.record(frame, inputs, visibility, kWidth, kHeight);
    frame.submitAndWait();
    EXPECT_FALSE(pass.growIfOverflowed());
    EXPECT_GE(pass.stats().setupTriangles, 2000u);

    const Visibility roomy = rasterizeClipTriangles(context(), input, kWidth, kHeight, scheme);
    EXPECT_EQ(visibility.download<glm::uvec2>(), roomy.entries);
  }
}

// One 8x8 tile under 200,000 triangles: the tile-lists scheme walks the tile's list in one loop,
// and llvmpipe (Mesa 22.3) ends an invocation's loops after 65535 iterations, silently. There
// the frame is refused in one line naming the scheme that renders it; where the walk finishes,
// it matches the 64-bit atomics' picture. Half walked, it matched neither (checked).
TEST_F(CapacityTest, ATileListPastTheLoopBudgetIsRefusedNotHalfWalked) {
  constexpr uint32_t kSide = 8, kTriangles = 200000;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> z(0.05f, 0.95f);
  ClipTriangles input;
  // Each a small triangle over one pixel centre, about 3,100 a pixel at random depths: a walk
  // ended after 65535 of the tile's entries misses most pixels' nearest.
  for (uint32_t i = 0; i < kTriangles; ++i) {
    const float depth = z(rng);
    const glm::vec2 c((float(i % kSide) + 0.5f) / kSide * 2.0f - 1.0f, (float(i / kSide % kSide) + 0.5f) / kSide * 2.0f - 1.0f);
    input.add({c.x - 0.1f, c.y - 0.1f, depth, 1.0f}, {c.x + 0.1f, c.y - 0.1f, depth, 1.0f}, {c.x, c.y + 0.1f, depth, 1.0f});
  }
  const UploadedTriangles uploaded(context(), input);
  const passes::RasterInputs inputs = uploaded.inputs(kTriangles);
  vk::Buffer visibility(context(), passes::RasterizePass::visibilityBytes(kSide, kSide), vk::MemoryUse::Device,
                        "visibility");
  passes::RasterizePass pass(context(), passes::VisibilityScheme::TileLists);
  pass.reserve(kTriangles, kSide, kSide);
  vk::FrameRecorder frame(context());
  frame.begin();
  pass.record(frame, inputs, visibility, kSide, kSide);
  frame.submitAndWait();
  // Refused in one line, or walked whole (drivers without the budget: Mesa 25's llvmpipe).
  bool refused = false;
  try {
    EXPECT_FALSE(pass.growIfOverflowed());
  } catch (const Error& e) {
    refused = true;
    const std::string message = e.what();
    EXPECT_NE(message.find("65535 triangles"), std::string::npos) << message;
    EXPECT_NE(message.find("int64-atomics"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  std::printf("[ tile list] %u triangles in one tile on %s: %s\n", kTriangles, context().info().name.c_str(),
              refused ? "refused" : "walked whole");
  if (refused) return;
  const Visibility atomics =
      rasterizeClipTriangles(context(), input, kSide, kSide, passes::VisibilityScheme::Int64Atomics);
  EXPECT_EQ(visibility.download<glm::uvec2>(), atomics.entries);
}

// Triangles crossing the near plane go through a list for clip_triangles, sized by estimate
// too: more of them than the list holds must grow it, not drop them.
TEST_F(CapacityTest, ClipListOverflowGrowsAndLosesNoTriangle) {
  constexpr uint32_t kWidth = 40, kHeight = 30;
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> xy(-0.8f, 0.8f), z(0.1f, 0.9f);
  ClipTriangles input;
  for (int i = 0; i < 1500; ++i) {
    const glm::vec2 c(xy(rng), xy(rng));
    const float depth = z(rng);
    // The third vertex lies behind the eye (w < 0, z < 0): every triangle needs clipping.
    input.add({c.x - 0.3f, c.y, depth, 1.0f}, {c.x + 0.3f, c.y, depth, 1.0f}, {c.x, c.y + 0.3f, -0.5f, -1.0f});
  }
  const Visibility visibility =
      rasterizeClipTriangles(context(), input, kWidth, kHeight, passes::VisibilityScheme::Int64Atomics);
  EXPECT_GE(visibility.stats.regrowths, 1u) << "1500 triangles to clip should outgrow the first clip list";
  // Every clipped triangle is in: the result is the C++ reference's, bit for bit.
  const auto setup = reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kWidth, kHeight);
  EXPECT_EQ(visibility.stats.setupTriangles, setup.size());
  EXPECT_EQ(visibility.entries, reference::rasterizeReference(setup, kWidth, kHeight).entries);
}

}  // namespace
}  // namespace hmb::test
