// A context on an engine's own Vulkan objects: the engine's instance and device, made here as an
// engine would make them, rendered on, and still the engine's (alive, usable) afterwards.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "tests/support/engine_device.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

RenderSettings hybridAt(uint32_t width, uint32_t height) {
  RenderSettings settings;
  settings.method = Method::Hybrid;
  settings.width = width;
  settings.height = height;
  return settings;
}

// Rendered on the engine's device, a frame equals the one the library renders on its own; the
// device outlives the context, and no validation message comes up on either side.
TEST(AdoptedContextTest, RendersOnTheEnginesDeviceAndLeavesItToTheEngine) {
  const scene::Scene scene = scene::loadScene("living-room");
  Engine engine(/*enableFeatures=*/true);
  io::Rgba8Image adoptedImage;
  {
    vk::Context context(engine.adopted(), countingOptions());
    EXPECT_TRUE(context.adopted());
    EXPECT_EQ(context.device(), engine.device);
    EXPECT_EQ(context.info().int64BufferAtomics, engine.shaderInt64 && engine.int64Atomics);
    Renderer renderer(context);
    adoptedImage = renderer.render(scene, hybridAt(96, 54)).display;
    EXPECT_EQ(context.validationErrors(), 0u);
  }
  EXPECT_TRUE(engine.stillUsable());
  EXPECT_TRUE(engine.errors.empty()) << engine.errors.front();

  vk::Context own(countingOptions());
  Renderer renderer(own);
  EXPECT_EQ(adoptedImage.pixels, renderer.render(scene, hybridAt(96, 54)).display.pixels);
}

// A device without the optional features still renders: the library uses only what was enabled
// (on a CPU device the tile-lists rasterizer, elsewhere the 32-bit path without 64-bit atomics).
TEST(AdoptedContextTest, UsesOnlyTheFeaturesTheEngineEnabled) {
  Engine engine(/*enableFeatures=*/false);
  vk::Context context(engine.adopted(), countingOptions());
  EXPECT_FALSE(context.info().int64BufferAtomics);
  EXPECT_FALSE(context.info().bufferDeviceAddress);
  Renderer renderer(context);
  RenderSettings settings = hybridAt(48, 27);
  const RenderResult result = renderer.render(scene::loadScene("temple"), settings);
  EXPECT_EQ(result.visibilityScheme, context.profile().rasterTileLists ? "tile-lists" : "depth32-two-pass");
  EXPECT_EQ(context.validationErrors(), 0u);
}

// What the library cannot work with is a one-line error naming it.
TEST(AdoptedContextTest, WhatIsMissingIsAOneLineErrorNamingIt) {
  Engine engine(/*enableFeatures=*/false);
  const auto errorOf = [&](vk::AdoptedVulkan adopted, vk::ContextOptions options) {
    try {
      vk::Context context(adopted, options);
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
      return message;
    }
    return std::string("adopted");
  };
  vk::AdoptedVulkan badFamily = engine.adopted();
  badFamily.queueFamily = 99;
  EXPECT_NE(errorOf(badFamily, countingOptions()).find("queue family 99 does not exist"), std::string::npos);
  // One past the family's queues: no index below it is known to be missing (a family may have
  // many queues, of which the engine created only some).
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(engine.physicalDevice, &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(engine.physicalDevice, &familyCount, families.data());
  vk::AdoptedVulkan badQueue = engine.adopted();
  badQueue.queueIndex = families.at(badQueue.queueFamily).queueCount;
  EXPECT_NE(errorOf(badQueue, countingOptions()).find("queue " + std::to_string(badQueue.queueIndex) + " of family"),
            std::string::npos);
  vk::AdoptedVulkan noFloatControls = engine.adopted();
  noFloatControls.apiVersion = VK_API_VERSION_1_1;
  EXPECT_NE(errorOf(noFloatControls, countingOptions()).find("VK_KHR_shader_float_controls"), std::string::npos);
  vk::AdoptedVulkan old = engine.adopted();
  old.apiVersion = VK_API_VERSION_1_0;
  EXPECT_NE(errorOf(old, countingOptions()).find("Vulkan 1.1 or later"), std::string::npos);
  vk::ContextOptions byAddress = countingOptions();
  byAddress.bindByAddress = true;
  EXPECT_NE(errorOf(engine.adopted(), byAddress).find("bufferDeviceAddress"), std::string::npos);
  vk::AdoptedVulkan noDebug = engine.adopted();
  noDebug.debugUtils = false;
  EXPECT_NE(errorOf(noDebug, countingOptions()).find("VK_EXT_debug_utils"), std::string::npos);
  vk::AdoptedVulkan none;
  EXPECT_NE(errorOf(none, countingOptions()).find("must all be given"), std::string::npos);
  EXPECT_TRUE(engine.stillUsable());
  EXPECT_TRUE(engine.errors.empty()) << engine.errors.front();
}

}  // namespace
}  // namespace hmb::test
