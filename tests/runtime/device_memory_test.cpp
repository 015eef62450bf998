// Device memory accounting: every vk::Buffer's allocation is counted in its context while it
// lives, the peak holds the most counted at once, and a render reports its peak, the G-buffer's
// bytes per pixel and the mesh trees' bytes per triangle.
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
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
    settings.method = parseMethod(method);
    const RenderResult result = renderer.render(scene, settings);
    // Visibility (8), the layer's samples (16) and surfaces (16), its velocities (8).
    EXPECT_EQ(result.memory.gbufferBytesPerPixel, 48.0) << method;
    EXPECT_GE(result.memory.peakBytes, uint64_t(48 * 96 * 54)) << method;
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
    settings.method = parseMethod(method);
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

namespace hmb::test {
namespace {

// A discrete GPU without resizable BAR (a context that pretends its host-visible device-local
// heap holds 256 MiB): the kernels' working memory goes to device-local memory the host cannot
// map, uploads and read-backs through staging in system memory, so a 1920x1080 hybrid frame
// (300+ MiB) renders, the BAR heap stays empty, and the image is the one the plain device makes.
TEST(DeviceMemoryLimitTest, HybridAt1080pRendersOnADeviceWithA256MiBHostVisibleHeap) {
  constexpr uint64_t kBar = 256ull << 20;
  vk::ContextOptions options;
  options.validation = true;
  options.hostVisibleDeviceLocalBytes = kBar;
  vk::Context discrete(options);
  const VkPhysicalDeviceMemoryProperties& memory = discrete.memoryProperties();
  uint32_t barHeap = UINT32_MAX, vramHeap = UINT32_MAX;
  for (uint32_t h = 0; h < memory.memoryHeapCount; ++h) {
    if (!(memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)) continue;
    (memory.memoryHeaps[h].size == kBar ? barHeap : vramHeap) = h;
  }
  ASSERT_NE(barHeap, UINT32_MAX);
  ASSERT_NE(vramHeap, UINT32_MAX);

  vk::Buffer work(discrete, 1 << 20, vk::MemoryUse::Device, "working memory");
  EXPECT_EQ(work.mapped(), nullptr) << "device-local memory of a discrete GPU is not host-visible";
  const std::vector<uint32_t> values = {1, 2, 3, 4};
  work.upload(std::span<const uint32_t>(values));
  std::vector<uint32_t> readBack = work.download<uint32_t>();
  readBack.resize(values.size());
  EXPECT_EQ(readBack, values);

  const scene::Scene scene = scene::loadScene("living-room");
  RenderSettings settings;
  settings.method = Method::Hybrid;  // the paper's: the ray mask's and the reveal's buffers too
  settings.width = 1920;
  settings.height = 1080;
  Renderer renderer(discrete);
  const RenderResult result = renderer.render(scene, settings);
  EXPECT_GT(result.memory.peakBytes, kBar) << "the frame should need more than the BAR heap holds";
  EXPECT_GT(result.hybrid->maskPixels, 0u);
  EXPECT_EQ(discrete.heapInUse(barHeap), 0u);
  EXPECT_GT(discrete.heapInUse(vramHeap), 0u);
  EXPECT_EQ(discrete.validationErrors(), 0u);

  // The same frame on the device as it is (one host-visible heap): the same image.
  vk::ContextOptions plainOptions;
  vk::Context plain(plainOptions);
  Renderer plainRenderer(plain);
  const RenderResult expected = plainRenderer.render(scene, settings);
  ASSERT_EQ(result.image.layers.size(), expected.image.layers.size());
  for (size_t i = 0; i < result.image.layers.size(); ++i) {
    EXPECT_EQ(result.image.layers[i].values, expected.image.layers[i].values) << result.image.layers[i].name;
    EXPECT_EQ(result.image.layers[i].ids, expected.image.layers[i].ids) << result.image.layers[i].name;
  }
  EXPECT_EQ(result.display.pixels, expected.display.pixels);
}

}  // namespace
}  // namespace hmb::test
