// An engine as the adopted-context and engine-backend tests make one: its own instance (with
// the validation layer and its own messenger), device, compute queue, command buffers and
// buffers, none of them the library's.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <vulkan/vulkan.h>

#include "hmblur/context.h"

namespace hmb::test {

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
    if (commandPool) vkDestroyCommandPool(device, commandPool, nullptr);
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

  // A host-visible storage buffer of the engine's, holding `bytes` (zeros where bytes is empty).
  struct OwnBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkDeviceSize size = 0;
  };
  OwnBuffer makeBuffer(VkDeviceSize size, std::span<const std::byte> bytes = {});
  std::vector<std::byte> read(const OwnBuffer& buffer) const;
  void destroy(OwnBuffer& buffer);
  // A 2D image of the engine's (optimal tiling, device memory) holding `texels` (tightly packed
  // rows, row 0 at the top), with a view of its colour or depth aspect, in `layout`.
  struct OwnImage {
    VkImage image = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0, texelBytes = 0;
  };
  OwnImage makeImage(uint32_t width, uint32_t height, VkFormat format, uint32_t texelBytes, VkImageUsageFlags usage,
                     std::span<const std::byte> texels, VkImageLayout layout);
  // Its texels, read back through a buffer; the image is in `layout`, and stays there.
  std::vector<std::byte> read(const OwnImage& image, VkImageLayout layout);
  void destroy(OwnImage& image);
  // A primary command buffer of the engine's pool, recording; submitAndWait ends and runs it.
  VkCommandBuffer beginCommands();
  void submitAndWait(VkCommandBuffer commands);

  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  bool shaderInt64 = false, int64Atomics = false, bufferDeviceAddress = false;
  std::vector<std::string> errors;
  VkCommandPool commandPool = VK_NULL_HANDLE;
};

// Options of a library context on an engine's objects in the tests: validation messages
// counted, no pipeline cache on disk.
inline vk::ContextOptions countingOptions() {
  vk::ContextOptions options;
  options.validation = true;
  options.pipelineCacheFolder.clear();
  return options;
}

}  // namespace hmb::test
