// A context on an engine's own Vulkan objects: the engine's instance and device, made here as an
// engine would make them, rendered on, and still the engine's (alive, usable) afterwards.
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/error.h"
#include "runtime/renderer.h"
#include "runtime/vulkan/context.h"
#include "scenes/load_scene.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

// What an engine owns: an instance with the validation layer and its own messenger, a device
// with one compute queue and the features it chose to enable.
class Engine {
 public:
  explicit Engine(bool enableFeatures) {
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "an engine";
    app.apiVersion = VK_API_VERSION_1_2;
    VkInstanceCreateInfo instanceInfo{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    instanceInfo.pApplicationInfo = &app;
    instanceInfo.enabledLayerCount = 1;
    instanceInfo.ppEnabledLayerNames = &layer;
    instanceInfo.enabledExtensionCount = 1;
    instanceInfo.ppEnabledExtensionNames = &extension;
    EXPECT_EQ(vkCreateInstance(&instanceInfo, nullptr, &instance), VK_SUCCESS);

    VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messengerInfo.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
    messengerInfo.pfnUserCallback = [](VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                       const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) -> VkBool32 {
      static_cast<Engine*>(user)->errors.emplace_back(data->pMessage ? data->pMessage : "");
      return VK_FALSE;
    };
    messengerInfo.pUserData = this;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    EXPECT_EQ(create(instance, &messengerInfo, nullptr, &messenger), VK_SUCCESS);

    uint32_t count = 1;
    vkEnumeratePhysicalDevices(instance, &count, &physicalDevice);
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &families, nullptr);
    std::vector<VkQueueFamilyProperties> properties(families);
    vkGetPhysicalDeviceQueueFamilyProperties(physicalDevice, &families, properties.data());
    for (uint32_t f = 0; f < families; ++f)
      if (properties[f].queueFlags & VK_QUEUE_COMPUTE_BIT) {
        queueFamily = f;
        break;
      }

    VkPhysicalDeviceBufferDeviceAddressFeatures addresses{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
    VkPhysicalDeviceShaderAtomicInt64Features atomics{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES};
    atomics.pNext = &addresses;
    VkPhysicalDeviceFeatures2 supported{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    supported.pNext = &atomics;
    vkGetPhysicalDeviceFeatures2(physicalDevice, &supported);
    VkPhysicalDeviceFeatures2 enabled{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    if (enableFeatures) {
      enabled = supported;
      shaderInt64 = supported.features.shaderInt64;
      int64Atomics = atomics.shaderBufferInt64Atomics;
      bufferDeviceAddress = addresses.bufferDeviceAddress;
    } else {
      enabled.pNext = nullptr;
    }
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &enabled;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    EXPECT_EQ(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), VK_SUCCESS);
  }

  ~Engine() {
    vkDestroyDevice(device, nullptr);
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance, messenger, nullptr);
    vkDestroyInstance(instance, nullptr);
  }

  vk::AdoptedVulkan adopted() const {
    vk::AdoptedVulkan a;
    a.instance = instance;
    a.apiVersion = VK_API_VERSION_1_2;
    a.debugUtils = true;
    a.physicalDevice = physicalDevice;
    a.device = device;
    a.queueFamily = queueFamily;
    a.shaderInt64 = shaderInt64;
    a.shaderBufferInt64Atomics = int64Atomics;
    a.bufferDeviceAddress = bufferDeviceAddress;
    return a;
  }

  // The device still does what a device does: a buffer made, the queue idle.
  bool stillUsable() const {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = 256;
    info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    VkBuffer buffer = VK_NULL_HANDLE;
    if (vkCreateBuffer(device, &info, nullptr, &buffer) != VK_SUCCESS) return false;
    vkDestroyBuffer(device, buffer, nullptr);
    VkQueue queue = VK_NULL_HANDLE;
    vkGetDeviceQueue(device, queueFamily, 0, &queue);
    return queue != VK_NULL_HANDLE && vkQueueWaitIdle(queue) == VK_SUCCESS && vkDeviceWaitIdle(device) == VK_SUCCESS;
  }

  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  bool shaderInt64 = false, int64Atomics = false, bufferDeviceAddress = false;
  std::vector<std::string> errors;
};

vk::ContextOptions countingOptions() {
  vk::ContextOptions options;
  options.validation = true;
  options.pipelineCacheFolder.clear();
  return options;
}

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
  EXPECT_EQ(result.visibilityScheme, context.info().type == "cpu" ? "tile-lists" : "depth32-two-pass");
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
  vk::AdoptedVulkan badQueue = engine.adopted();
  badQueue.queueIndex = 5;
  EXPECT_NE(errorOf(badQueue, countingOptions()).find("queue 5 of family"), std::string::npos);
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
