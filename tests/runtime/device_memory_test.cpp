// Device memory accounting: every vk::Buffer's allocation is counted in its context while it
// lives, the peak holds the most counted at once, and a render reports its peak, the G-buffer's
// bytes per pixel and the mesh trees' bytes per triangle.
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "runtime/error.h"
#include "runtime/renderer.h"
#include "runtime/vulkan/buffer.h"
#include "scenes/load_scene.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using DeviceMemoryTest = VulkanTest;

TEST_F(DeviceMemoryTest, BuffersAreCountedWhileTheyLive) {
  const vk::Context& c = context();
  const uint64_t before = c.memoryInUse();
  c.resetMemoryPeak();
  {
    vk::Buffer a(c, 1 << 20, vk::MemoryUse::Device, "test a");
    EXPECT_GE(c.memoryInUse(), before + (1 << 20));
    vk::Buffer b(c, 3 << 20, vk::MemoryUse::Device, "test b");
    EXPECT_GE(c.memoryInUse(), before + (4 << 20));
    vk::Buffer moved = std::move(b);  // counted once, released once
    EXPECT_GE(c.memoryInUse(), before + (4 << 20));
    EXPECT_LT(c.memoryInUse(), before + (5 << 20));
  }
  EXPECT_EQ(c.memoryInUse(), before);
  EXPECT_GE(c.memoryPeak(), before + (4 << 20));
  c.resetMemoryPeak();
  EXPECT_EQ(c.memoryPeak(), before);
}

TEST_F(DeviceMemoryTest, RenderReportsItsPeakAndPerPixelAndPerTriangleBytes) {
  Renderer renderer(context());
  const scene::Scene scene = scene::loadScene("living-room");
  RenderSettings settings;
  settings.width = 96;
  settings.height = 54;
  for (const char* method : {"postprocess", "hybrid"}) {
    settings.method = method;
    const RenderResult result = renderer.render(scene, settings);
    // Visibility (8), colour (16), normal-depth (16), velocity (8) and object id (4).
    EXPECT_EQ(result.memory.gbufferBytesPerPixel, 52.0) << method;
    EXPECT_GE(result.memory.peakBytes, uint64_t(52 * 96 * 54)) << method;
    EXPECT_GE(result.memory.peakBytes, context().memoryInUse()) << method;
    EXPECT_EQ(result.memory.bvhAllocatedBytesPerTriangle.has_value(), std::string(method) == "hybrid") << method;
    if (result.memory.bvhBuiltBytesPerTriangle) {
      // A tree holds at least one index per triangle and its root; the mesh trees, built once,
      // are kept in buffers of their own size (the worst case allocated for the build is freed).
      EXPECT_GT(*result.memory.bvhBuiltBytesPerTriangle, 4.0);
      EXPECT_DOUBLE_EQ(*result.memory.bvhBuiltBytesPerTriangle, *result.memory.bvhAllocatedBytesPerTriangle);
    }
  }
}

// A device with little memory (a context that pretends its heaps hold 32 MiB): a frame whose
// buffers each fit but together do not fails with one clear line before the allocation that
// would overflow the heap, frees what it had taken, and the renderer still renders a frame
// that fits.
TEST(DeviceMemoryLimitTest, AFrameLargerThanTheHeapIsAClearErrorAndLeavesNothingBehind) {
  vk::ContextOptions options;
  options.validation = true;
  options.memoryLimitBytes = uint64_t(32) << 20;
  vk::Context small(options);
  EXPECT_EQ(small.info().deviceLocalBytes, options.memoryLimitBytes);
  Renderer renderer(small);
  const scene::Scene scene = scene::loadScene("temple");
  RenderSettings settings;
  for (const char* method : {"sharp", "hybrid", "reference"}) {
    settings.method = method;
    // No buffer over 16 MiB, but 52 B of G-buffer per pixel alone is 52 MiB (the reference:
    // 36 B of beauty, sum and display per pixel).
    settings.width = 1024;
    settings.height = 1024;
    settings.reference.samplesPerPixel = 1;
    try {
      renderer.render(scene, settings);
      ADD_FAILURE() << method << ": a 1024x1024 frame rendered in 32 MiB";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("device memory"), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
    EXPECT_LE(small.memoryInUse(), options.memoryLimitBytes) << method;
    for (uint32_t h = 0; h < small.memoryProperties().memoryHeapCount; ++h)
      EXPECT_LE(small.heapInUse(h), small.memoryProperties().memoryHeaps[h].size) << method;

    settings.width = 64;
    settings.height = 36;
    const RenderResult fits = renderer.render(scene, settings);
    EXPECT_LE(fits.memory.peakBytes, options.memoryLimitBytes) << method;
  }
  EXPECT_EQ(small.validationErrors(), 0u);
}

}  // namespace
}  // namespace hmb::test
