// The Vulkan instance, the chosen compute device and its queue, and the debug messenger that
// counts validation messages (tests fail on any error).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "hmblur/device_profile.h"

namespace hmb::vk {

class KernelStore;
class PipelineCache;

// Where compiled kernels are kept across runs unless the options say otherwise
// (pipeline_cache.h).
std::filesystem::path defaultPipelineCacheFolder();

// What the report and `hmblur list-devices` say about a device.
struct DeviceInfo {
  uint32_t index = 0;
  std::string name;
  std::string type;  // "discrete-gpu", "integrated-gpu", "virtual-gpu", "cpu", "other"
  std::string driverName;
  std::string driverInfo;
  std::string apiVersion;  // "1.3.230"
  uint32_t vendorId = 0;
  uint32_t deviceId = 0;
  bool computeCapable = false;
  bool int64BufferAtomics = false;  // shaderBufferInt64Atomics
  bool bufferDeviceAddress = false;  // kernels can bind groups of buffers as tables of addresses
  bool timestamps = false;          // the compute queue has timestamp bits
  uint64_t timestampMask = 0;       // the valid bits of a timestamp on that queue
  double timestampPeriodNs = 0.0;
  uint64_t maxStorageBufferRange = 0;
  uint64_t deviceLocalBytes = 0;  // the largest device-local heap
  uint32_t maxComputeWorkGroupCount[3] = {0, 0, 0};
  uint32_t maxComputeWorkGroupSizeX = 0;       // what the device profile shapes workgroups within
  uint32_t maxComputeWorkGroupInvocations = 0;
  uint32_t subgroupSize = 0;
  // Kernels may declare SignedZeroInfNanPreserve for 32-bit floats (shaderSignedZeroInfNanPreserveFloat32,
  // Vulkan 1.2 or VK_KHR_shader_float_controls): every kernel does (kernels/shared/float_controls.glsl).
  bool preservesInfNan = false;
};

struct ContextOptions {
  int deviceIndex = -1;                // -1: choose (discrete GPU first, then any compute device)
  bool validation = false;             // enable VK_LAYER_KHRONOS_validation and count its messages
  bool synchronizationValidation = false;
  bool disableInt64Atomics = false;    // pretend the device lacks them (tests of fallbacks)
  uint64_t memoryLimitBytes = 0;       // > 0: pretend no memory heap holds more (tests of running out)
  uint32_t storageBufferLimit = 0;     // > 0: pretend no stage or set takes more storage buffers
  uint32_t texelBufferLimit = 0;       // > 0: pretend texel views hold at most this many texels
  uint32_t storageBufferRangeLimit = 0;  // > 0: pretend a storage buffer binding holds at most this many bytes
  // Kernels with an address build (vk::ComputeKernel) bind their groups of buffers as tables of
  // device addresses: always when true, else only where their bindings exceed the device's limits.
  bool bindByAddress = false;
  // > 0: pretend a discrete GPU without resizable BAR, whose host-visible device-local heap holds
  // this many bytes (256 MiB on such GPUs): device-local memory the host cannot map, that small
  // heap, and system memory for staging. Tests that frames fit such devices.
  uint64_t hostVisibleDeviceLocalBytes = 0;
  // Whose choices the passes make (device_profile.h): the device type's, or the one forced.
  DeviceProfileChoice deviceProfile = DeviceProfileChoice::Auto;
  // Where compiled kernels are kept across runs (pipeline_cache.h); empty: in memory only.
  std::filesystem::path pipelineCacheFolder = defaultPipelineCacheFolder();
};

// An engine's own Vulkan objects, for a context that adopts them (an engine's fallback backend):
// the library records and submits its work there and never destroys them. Vulkan cannot be
// asked what a device was created with, so the engine says which of the features the library
// can use it enabled; the library uses no others. It submits to and waits on the given queue,
// which the engine must not use from another thread meanwhile (Vulkan's external
// synchronization rule).
struct AdoptedVulkan {
  VkInstance instance = VK_NULL_HANDLE;
  uint32_t apiVersion = 0;  // the instance's VkApplicationInfo::apiVersion: 1.1 or later
  bool debugUtils = false;  // VK_EXT_debug_utils enabled on the instance (ContextOptions::validation)
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;  // must have VK_QUEUE_COMPUTE_BIT
  uint32_t queueIndex = 0;
  // Enabled at vkCreateDevice. Without them the rasterizer takes its 32-bit visibility path and
  // kernels bind buffers by name (a device with too few bindings then cannot run them).
  bool shaderInt64 = false;
  bool shaderBufferInt64Atomics = false;
  bool bufferDeviceAddress = false;
  // VK_KHR_shader_float_controls enabled at vkCreateDevice: needed only where the instance or the
  // device is older than Vulkan 1.2 (every kernel keeps NaN and infinity: DeviceInfo::preservesInfNan).
  bool shaderFloatControls = false;
};

class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  // Adopts the engine's objects (throws hmb::Error naming what is missing or wrong). Of the
  // options, those about a device's choice (deviceIndex) do not apply; validation counts the
  // messages the library's work brings up, through a messenger of its own on the instance.
  explicit Context(const AdoptedVulkan& adopted, const ContextOptions& options = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  // Lists the devices without creating a logical device.
  static std::vector<DeviceInfo> listDevices();

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physicalDevice() const { return physicalDevice_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queueFamily() const { return queueFamily_; }
  VkCommandPool commandPool() const { return commandPool_; }
  bool adopted() const { return adopted_; }  // the instance and device are the engine's
  // Every kernel's pipeline is made through it (and kept on disk when the options say where).
  const PipelineCache& pipelineCache() const { return *pipelineCache_; }
  // The kernels made on this device so far, shared by every pass that uses them.
  KernelStore& kernelStore() const { return *kernelStore_; }
  const DeviceInfo& info() const { return info_; }
  // Every choice that differs between CPU devices and GPUs (device_profile.h).
  const DeviceProfile& profile() const { return profile_; }
  const VkPhysicalDeviceLimits& limits() const { return limits_; }
  bool validationEnabled() const { return validationEnabled_; }
  const ContextOptions& options() const { return options_; }

  // Memory type with all required flags among those the buffer allows (memoryTypeBits of its
  // requirements); prefers the ones that also have the preferred flags. Returns UINT32_MAX
  // when none fits. Types and heaps are those of memoryProperties(), which a pretend device
  // (ContextOptions) changes; allocate with allocationType() of the type found.
  uint32_t findMemoryType(uint32_t allowedTypes, VkMemoryPropertyFlags required,
                          VkMemoryPropertyFlags preferred = 0) const;
  // The memory type of buffers only kernels touch: device-local, and host-visible too only
  // where that memory is in the device's largest device-local heap (CPU devices, integrated
  // GPUs, resizable BAR), so a small BAR heap is never filled with working memory.
  uint32_t findDeviceMemoryType(uint32_t allowedTypes) const;
  const VkPhysicalDeviceMemoryProperties& memoryProperties() const { return memoryProperties_; }
  uint32_t allocationType(uint32_t type) const { return allocationTypes_.at(type); }

  // Device memory the buffers of this context hold now (in all heaps, and in one heap), and
  // the most they held at once since creation or the last resetMemoryPeak() (vk::Buffer
  // reports its allocations here and checks each against what its heap has left).
  uint64_t memoryInUse() const;
  uint64_t heapInUse(uint32_t heap) const { return heapInUse_.at(heap).load(); }
  uint64_t memoryPeak() const { return memoryPeak_.load(); }
  void resetMemoryPeak() const { memoryPeak_.store(memoryInUse()); }
  void countAllocation(uint32_t heap, uint64_t bytes) const;
  void countRelease(uint32_t heap, uint64_t bytes) const;

  // Records commands into a one-time command buffer, submits it and waits.
  void submitAndWait(const std::function<void(VkCommandBuffer)>& record) const;
  void submitAndWait(VkCommandBuffer commandBuffer) const;

  // Since creation: the library's own waits on the device (submitAndWait) and the reads of
  // buffer contents back to the host (vk::Buffer::read), so a caller can hold a path to neither
  // (an engine's recorded frame).
  uint64_t hostWaits() const { return hostWaits_.load(); }
  uint64_t hostReadbacks() const { return hostReadbacks_.load(); }
  // Both: every time the host waited on the device or read its memory (vk::FrameShape::hostWaits).
  uint64_t hostRoundTrips() const { return hostWaits() + hostReadbacks(); }
  void countReadback() const { ++hostReadbacks_; }

  // Validation messages seen since creation (errors and warnings counted separately).
  uint32_t validationErrors() const { return validationErrors_.load(); }
  uint32_t validationWarnings() const { return validationWarnings_.load(); }
  std::vector<std::string> validationMessages() const;

 private:
  void releaseHandles();
  void readDevice(const ContextOptions& options);        // limits, memory, the options' pretences
  void createOwnObjects(const ContextOptions& options);  // command pool, pipeline cache
  VkDebugUtilsMessengerCreateInfoEXT messengerCreateInfo();
  void createMessenger(const VkDebugUtilsMessengerCreateInfoEXT& info);  // counts into this context
  void pretendDiscreteMemory(uint64_t barBytes);
  static VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT types,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  uint32_t queueFamily_ = 0;
  VkCommandPool commandPool_ = VK_NULL_HANDLE;
  std::unique_ptr<PipelineCache> pipelineCache_;
  std::unique_ptr<KernelStore> kernelStore_;
  VkPhysicalDeviceLimits limits_{};
  VkPhysicalDeviceMemoryProperties memoryProperties_{};
  std::array<uint32_t, VK_MAX_MEMORY_TYPES> allocationTypes_{};  // memoryProperties_ type -> the device's
  DeviceInfo info_;
  DeviceProfile profile_;
  ContextOptions options_;
  bool adopted_ = false;
  bool validationEnabled_ = false;

  mutable std::atomic<uint64_t> memoryPeak_{0};
  mutable std::array<std::atomic<uint64_t>, VK_MAX_MEMORY_HEAPS> heapInUse_{};
  std::atomic<uint32_t> validationErrors_{0};
  mutable std::atomic<uint64_t> hostWaits_{0};
  mutable std::atomic<uint64_t> hostReadbacks_{0};
  std::atomic<uint32_t> validationWarnings_{0};
  mutable std::mutex messagesMutex_;
  std::vector<std::string> messages_;
};

}  // namespace hmb::vk
