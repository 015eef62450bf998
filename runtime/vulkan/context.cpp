#include "hmblur/context.h"

#include <algorithm>
#include <cstring>
#include <memory>

#include "hmblur/error.h"
#include "runtime/vulkan/check.h"
#include "runtime/vulkan/kernel_store.h"
#include "runtime/vulkan/pipeline_cache.h"

namespace hmb::vk {

std::filesystem::path defaultPipelineCacheFolder() { return PipelineCache::defaultFolder(); }
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr uint32_t kMaxKeptMessages = 64;
// Why a device cannot run the kernels, which all keep NaN and infinity (kernels/shared/float_controls.glsl).
constexpr const char* kNoInfNanPreserve =
    "cannot keep NaN and infinity in its kernels (shaderSignedZeroInfNanPreserveFloat32 is false), and every "
    "kernel relies on it to keep bad input out of the images";

bool hasInstanceLayer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

bool hasInstanceExtension(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateInstanceExtensionProperties(nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

std::string versionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

const char* typeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual-gpu";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "cpu";
    default: return "other";
  }
}

// Lower is better: the order in which devices are chosen when none is named.
int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

std::vector<VkQueueFamilyProperties> queueFamilies(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  return families;
}

// Whether the queue family times work (timestamps), and the mask of its valid bits.
void describeTimestamps(DeviceInfo& info, const VkQueueFamilyProperties& family, float timestampPeriod) {
  const uint32_t bits = family.timestampValidBits;
  info.timestamps = bits > 0 && timestampPeriod > 0.0f;
  info.timestampMask = bits >= 64 ? ~0ull : ((1ull << bits) - 1);
}

// The compute queue family: compute with timestamps first, then any compute family.
int pickQueueFamily(VkPhysicalDevice device) {
  const std::vector<VkQueueFamilyProperties> families = queueFamilies(device);
  const auto count = static_cast<uint32_t>(families.size());
  int best = -1;
  for (uint32_t i = 0; i < count; ++i) {
    if (!(families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) continue;
    if (best < 0) best = static_cast<int>(i);
    if (families[i].timestampValidBits > 0) return static_cast<int>(i);
  }
  return best;
}

DeviceInfo describe(VkPhysicalDevice device, uint32_t index) {
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(device, &props);

  DeviceInfo info;
  info.index = index;
  info.name = props.deviceName;
  info.type = typeName(props.deviceType);
  info.apiVersion = versionString(props.apiVersion);
  info.vendorId = props.vendorID;
  info.deviceId = props.deviceID;
  info.timestampPeriodNs = props.limits.timestampPeriod;
  info.maxStorageBufferRange = props.limits.maxStorageBufferRange;
  std::copy(std::begin(props.limits.maxComputeWorkGroupCount), std::end(props.limits.maxComputeWorkGroupCount),
            std::begin(info.maxComputeWorkGroupCount));
  info.maxComputeWorkGroupSizeX = props.limits.maxComputeWorkGroupSize[0];
  info.maxComputeWorkGroupInvocations = props.limits.maxComputeWorkGroupInvocations;

  const bool vulkan12 = props.apiVersion >= VK_API_VERSION_1_2;
  const bool driverPropsExt = hasDeviceExtension(device, VK_KHR_DRIVER_PROPERTIES_EXTENSION_NAME);
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceFloatControlsProperties floatControls{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FLOAT_CONTROLS_PROPERTIES};
  const bool floatControlsKnown =
      vulkan12 || hasDeviceExtension(device, VK_KHR_SHADER_FLOAT_CONTROLS_EXTENSION_NAME);
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &subgroup;
  void** next = &subgroup.pNext;
  if (vulkan12 || driverPropsExt) {
    *next = &driver;
    next = &driver.pNext;
  }
  if (floatControlsKnown) *next = &floatControls;
  vkGetPhysicalDeviceProperties2(device, &props2);
  info.subgroupSize = subgroup.subgroupSize;
  info.preservesInfNan = floatControlsKnown && floatControls.shaderSignedZeroInfNanPreserveFloat32;
  if (vulkan12 || driverPropsExt) {
    info.driverName = driver.driverName;
    info.driverInfo = driver.driverInfo;
  }

  VkPhysicalDeviceShaderAtomicInt64Features atomic64{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES};
  VkPhysicalDeviceBufferDeviceAddressFeatures addresses{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
  if (vulkan12 || hasDeviceExtension(device, VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME)) {
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.pNext = &atomic64;
    if (vulkan12) atomic64.pNext = &addresses;
    vkGetPhysicalDeviceFeatures2(device, &features2);
    info.int64BufferAtomics = atomic64.shaderBufferInt64Atomics && features2.features.shaderInt64;
    info.bufferDeviceAddress = vulkan12 && addresses.bufferDeviceAddress;
  }

  const int family = pickQueueFamily(device);
  info.computeCapable = family >= 0;
  if (family >= 0) describeTimestamps(info, queueFamilies(device)[family], props.limits.timestampPeriod);

  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(device, &memory);
  for (uint32_t h = 0; h < memory.memoryHeapCount; ++h)
    if (memory.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.deviceLocalBytes = std::max<uint64_t>(info.deviceLocalBytes, memory.memoryHeaps[h].size);
  return info;
}

// A bare instance: enough to enumerate devices.
struct InstanceSetup {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  VkInstanceCreateFlags flags = 0;
};

VkInstance createInstance(const InstanceSetup& setup, const void* next) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "hybrid-mblur";
  app.pEngineName = "hmb";
  app.apiVersion = VK_API_VERSION_1_2;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = next;
  info.flags = setup.flags;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<uint32_t>(setup.layers.size());
  info.ppEnabledLayerNames = setup.layers.data();
  info.enabledExtensionCount = static_cast<uint32_t>(setup.extensions.size());
  info.ppEnabledExtensionNames = setup.extensions.data();

  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER)
    throw Error("no Vulkan driver found (install a driver; on Debian, mesa-vulkan-drivers provides lavapipe)");
  HMB_VK_CHECK(result);
  return instance;
}

InstanceSetup portableSetup() {
  InstanceSetup setup;
  // Lets portability implementations (e.g. layered drivers) be enumerated too.
  if (hasInstanceExtension(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME)) {
    setup.extensions.push_back(VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME);
    setup.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
  }
  return setup;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t count = 0;
  HMB_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  HMB_VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, devices.data()));
  return devices;
}

}  // namespace

std::vector<DeviceInfo> Context::listDevices() {
  const VkInstance instance = createInstance(portableSetup(), nullptr);
  std::vector<DeviceInfo> infos;
  try {
    const auto devices = physicalDevices(instance);
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));
  } catch (...) {
    vkDestroyInstance(instance, nullptr);
    throw;
  }
  vkDestroyInstance(instance, nullptr);
  return infos;
}

VkDebugUtilsMessengerCreateInfoEXT Context::messengerCreateInfo() {
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messengerInfo.pfnUserCallback = &Context::onDebugMessage;
  messengerInfo.pUserData = this;
  return messengerInfo;
}

void Context::createMessenger(const VkDebugUtilsMessengerCreateInfoEXT& info) {
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
  if (!create) throw Error("validation requested but vkCreateDebugUtilsMessengerEXT is missing (VK_EXT_debug_utils)");
  HMB_VK_CHECK(create(instance_, &info, nullptr, &messenger_));
}

Context::Context(const ContextOptions& options)
    : kernelStore_(std::make_unique<KernelStore>()), options_(options) {
  InstanceSetup setup = portableSetup();
  VkDebugUtilsMessengerCreateInfoEXT messengerInfo = messengerCreateInfo();

  const bool debugUtils = hasInstanceExtension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (options.validation) {
    if (!hasInstanceLayer(kValidationLayer))
      throw Error(std::string("validation requested but ") + kValidationLayer +
                  " is not installed (Debian: vulkan-validationlayers)");
    if (!debugUtils) throw Error("validation requested but VK_EXT_debug_utils is not available");
    setup.layers.push_back(kValidationLayer);
    validationEnabled_ = true;
  }
  if (validationEnabled_) setup.extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  // The messenger is chained at creation too, so instance creation itself is validated.
  VkValidationFeatureEnableEXT syncValidation = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &syncValidation;
  const void* next = nullptr;
  if (validationEnabled_) {
    next = &messengerInfo;
    if (options.synchronizationValidation) {
      features.pNext = &messengerInfo;
      next = &features;
    }
  }
  instance_ = createInstance(setup, next);

  try {
    if (validationEnabled_) createMessenger(messengerInfo);

    const auto devices = physicalDevices(instance_);
    if (devices.empty()) throw Error("no Vulkan device found (on Debian, mesa-vulkan-drivers provides lavapipe)");

    std::vector<DeviceInfo> infos;
    for (uint32_t i = 0; i < devices.size(); ++i) infos.push_back(describe(devices[i], i));

    int chosen = -1;
    if (options.deviceIndex >= 0) {
      if (options.deviceIndex >= static_cast<int>(devices.size()))
        throw Error("--device " + std::to_string(options.deviceIndex) + " does not exist: " +
                    std::to_string(devices.size()) + " device(s) found (see `hmblur list-devices`)");
      if (!infos[options.deviceIndex].computeCapable)
        throw Error("device " + std::to_string(options.deviceIndex) + " (" + infos[options.deviceIndex].name +
                    ") has no compute queue");
      if (!infos[options.deviceIndex].preservesInfNan)
        throw Error("device " + std::to_string(options.deviceIndex) + " (" + infos[options.deviceIndex].name +
                    ") " + kNoInfNanPreserve);
      chosen = options.deviceIndex;
    } else {
      int bestRank = 1 << 30;
      for (uint32_t i = 0; i < devices.size(); ++i) {
        if (!infos[i].computeCapable || !infos[i].preservesInfNan) continue;
        VkPhysicalDeviceProperties props{};
        vkGetPhysicalDeviceProperties(devices[i], &props);
        const int rank = typeRank(props.deviceType);
        if (rank < bestRank) {
          bestRank = rank;
          chosen = static_cast<int>(i);
        }
      }
      if (chosen < 0) {
        const bool anyCompute =
            std::any_of(infos.begin(), infos.end(), [](const DeviceInfo& d) { return d.computeCapable; });
        throw Error(anyCompute ? std::string("no Vulkan device with a compute queue can run the kernels: each ") +
                                     kNoInfNanPreserve
                               : std::string("no Vulkan device with a compute queue found"));
      }
    }

    physicalDevice_ = devices[chosen];
    info_ = infos[chosen];
    queueFamily_ = static_cast<uint32_t>(pickQueueFamily(physicalDevice_));
    readDevice(options);
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(physicalDevice_, &props);

    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = queueFamily_;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;

    // Only features that a kernel may use, and only where present.
    VkPhysicalDeviceFeatures available{};
    vkGetPhysicalDeviceFeatures(physicalDevice_, &available);
    VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
    features2.features.shaderInt64 = available.shaderInt64;
    VkPhysicalDeviceShaderAtomicInt64Features atomic64{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_INT64_FEATURES};
    std::vector<const char*> deviceExtensions;
    void** next = &features2.pNext;
    // Kernels bind groups of buffers (the trace scene, the shading scene, an image layer) as
    // tables of device addresses where the device has too few storage-buffer bindings.
    VkPhysicalDeviceBufferDeviceAddressFeatures addresses{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
    if (info_.bufferDeviceAddress) {
      addresses.bufferDeviceAddress = VK_TRUE;
      *next = &addresses;
      next = &addresses.pNext;
    }
    if (info_.int64BufferAtomics) {
      atomic64.shaderBufferInt64Atomics = VK_TRUE;
      *next = &atomic64;
      if (props.apiVersion < VK_API_VERSION_1_2)
        deviceExtensions.push_back(VK_KHR_SHADER_ATOMIC_INT64_EXTENSION_NAME);
    }
    // Every kernel declares SignedZeroInfNanPreserve: core in Vulkan 1.2, an extension before.
    if (props.apiVersion < VK_API_VERSION_1_2) deviceExtensions.push_back(VK_KHR_SHADER_FLOAT_CONTROLS_EXTENSION_NAME);
    // Portability implementations must enable this extension when they expose it.
    if (hasDeviceExtension(physicalDevice_, "VK_KHR_portability_subset"))
      deviceExtensions.push_back("VK_KHR_portability_subset");

    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.pNext = &features2;
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    deviceInfo.enabledExtensionCount = static_cast<uint32_t>(deviceExtensions.size());
    deviceInfo.ppEnabledExtensionNames = deviceExtensions.data();
    HMB_VK_CHECK(vkCreateDevice(physicalDevice_, &deviceInfo, nullptr, &device_));
    vkGetDeviceQueue(device_, queueFamily_, 0, &queue_);
    createOwnObjects(options);
  } catch (...) {
    releaseHandles();
    throw;
  }
}

Context::Context(const AdoptedVulkan& adopted, const ContextOptions& options)
    : kernelStore_(std::make_unique<KernelStore>()), options_(options), adopted_(true) {
  const auto require = [](bool ok, const std::string& what) {
    if (!ok) throw Error("the adopted Vulkan device: " + what);
  };
  require(adopted.instance && adopted.physicalDevice && adopted.device,
          "instance, physical device and device must all be given");
  require(adopted.apiVersion >= VK_API_VERSION_1_1,
          "needs an instance of Vulkan 1.1 or later (AdoptedVulkan::apiVersion says " +
              versionString(adopted.apiVersion) + ")");
  instance_ = adopted.instance;
  physicalDevice_ = adopted.physicalDevice;
  device_ = adopted.device;
  try {
    VkPhysicalDeviceProperties props{};
    vkGetPhysicalDeviceProperties(physicalDevice_, &props);
    require(props.apiVersion >= VK_API_VERSION_1_1, "the physical device supports only Vulkan " +
                                                        versionString(props.apiVersion) + "; 1.1 is needed");
    const std::vector<VkQueueFamilyProperties> families = queueFamilies(physicalDevice_);
    const auto familyCount = static_cast<uint32_t>(families.size());
    require(adopted.queueFamily < familyCount, "queue family " + std::to_string(adopted.queueFamily) +
                                                   " does not exist (" + std::to_string(familyCount) + " families)");
    const VkQueueFamilyProperties& family = families[adopted.queueFamily];
    require((family.queueFlags & VK_QUEUE_COMPUTE_BIT) != 0,
            "queue family " + std::to_string(adopted.queueFamily) + " has no compute (VK_QUEUE_COMPUTE_BIT)");
    require(adopted.queueIndex < family.queueCount, "queue " + std::to_string(adopted.queueIndex) + " of family " +
                                                        std::to_string(adopted.queueFamily) + " does not exist (" +
                                                        std::to_string(family.queueCount) + " queues)");
    require(!options.bindByAddress || adopted.bufferDeviceAddress,
            "binding by address needs bufferDeviceAddress (VkPhysicalDeviceBufferDeviceAddressFeatures) enabled "
            "at vkCreateDevice");
    require(!options.validation || adopted.debugUtils,
            "counting validation messages needs VK_EXT_debug_utils enabled on the instance");

    uint32_t index = 0;
    const auto devices = physicalDevices(instance_);
    for (uint32_t i = 0; i < devices.size(); ++i)
      if (devices[i] == physicalDevice_) index = i;
    info_ = describe(physicalDevice_, index);
    require(info_.preservesInfNan, kNoInfNanPreserve);
    require((adopted.apiVersion >= VK_API_VERSION_1_2 && props.apiVersion >= VK_API_VERSION_1_2) ||
                adopted.shaderFloatControls,
            "below Vulkan 1.2 the kernels need VK_KHR_shader_float_controls enabled at vkCreateDevice "
            "(AdoptedVulkan::shaderFloatControls)");
    // What the engine enabled, not what the device could: a kernel may use only those.
    info_.int64BufferAtomics = info_.int64BufferAtomics && adopted.shaderInt64 && adopted.shaderBufferInt64Atomics;
    info_.bufferDeviceAddress = info_.bufferDeviceAddress && adopted.bufferDeviceAddress;
    describeTimestamps(info_, family, props.limits.timestampPeriod);
    queueFamily_ = adopted.queueFamily;
    readDevice(options);
    vkGetDeviceQueue(device_, queueFamily_, adopted.queueIndex, &queue_);

    // The engine's instance keeps its own messengers; this one only counts what the library's
    // work brings up, as an owned context's does.
    if (options.validation) {
      createMessenger(messengerCreateInfo());
      validationEnabled_ = true;
    }
    createOwnObjects(options);
  } catch (...) {
    releaseHandles();
    throw;
  }
}

void Context::readDevice(const ContextOptions& options) {
  if (options.disableInt64Atomics) info_.int64BufferAtomics = false;
  VkPhysicalDeviceProperties props{};
  vkGetPhysicalDeviceProperties(physicalDevice_, &props);
  limits_ = props.limits;
  if (options.storageBufferLimit > 0) {
    limits_.maxPerStageDescriptorStorageBuffers =
        std::min(limits_.maxPerStageDescriptorStorageBuffers, options.storageBufferLimit);
    limits_.maxDescriptorSetStorageBuffers = std::min(limits_.maxDescriptorSetStorageBuffers, options.storageBufferLimit);
  }
  if (options.texelBufferLimit > 0)
    limits_.maxTexelBufferElements = std::min(limits_.maxTexelBufferElements, options.texelBufferLimit);
  if (options.storageBufferRangeLimit > 0) {
    limits_.maxStorageBufferRange = std::min(limits_.maxStorageBufferRange, options.storageBufferRangeLimit);
    info_.maxStorageBufferRange = limits_.maxStorageBufferRange;
  }
  vkGetPhysicalDeviceMemoryProperties(physicalDevice_, &memoryProperties_);
  for (uint32_t t = 0; t < memoryProperties_.memoryTypeCount; ++t) allocationTypes_[t] = t;
  if (options.hostVisibleDeviceLocalBytes > 0) pretendDiscreteMemory(options.hostVisibleDeviceLocalBytes);
  if (options.memoryLimitBytes > 0) {
    for (uint32_t h = 0; h < memoryProperties_.memoryHeapCount; ++h)
      memoryProperties_.memoryHeaps[h].size = std::min(memoryProperties_.memoryHeaps[h].size, options.memoryLimitBytes);
    info_.deviceLocalBytes = std::min(info_.deviceLocalBytes, options.memoryLimitBytes);
  }
  profile_ = makeDeviceProfile(info_, limits_.maxComputeWorkGroupSize[0], limits_.maxComputeWorkGroupInvocations,
                               options.deviceProfile);
}

void Context::createOwnObjects(const ContextOptions& options) {
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = queueFamily_;
  HMB_VK_CHECK(vkCreateCommandPool(device_, &poolInfo, nullptr, &commandPool_));
  pipelineCache_ = std::make_unique<PipelineCache>(device_, physicalDevice_, options.pipelineCacheFolder);
}

Context::~Context() { releaseHandles(); }

// What the context made is destroyed; an adopted instance and device are left to their owner
// (waiting on the adopted queue only: the engine's other queues are its own business).
void Context::releaseHandles() {
  if (device_) {
    if (adopted_ && queue_) vkQueueWaitIdle(queue_);
    if (!adopted_) vkDeviceWaitIdle(device_);
    if (kernelStore_) kernelStore_->clear();
    pipelineCache_.reset();
    if (commandPool_) vkDestroyCommandPool(device_, commandPool_, nullptr);
    if (!adopted_) vkDestroyDevice(device_, nullptr);
    device_ = VK_NULL_HANDLE;
    commandPool_ = VK_NULL_HANDLE;
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
    messenger_ = VK_NULL_HANDLE;
  }
  if (instance_) {
    if (!adopted_) vkDestroyInstance(instance_, nullptr);
    instance_ = VK_NULL_HANDLE;
  }
}

void Context::pretendDiscreteMemory(uint64_t barBytes) {
  // Every pretend type is backed by the device's first memory type that is host-visible and
  // coherent (on a CPU device that is all of its memory); only the flags and heaps differ.
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  uint32_t backing = UINT32_MAX;
  for (uint32_t t = 0; t < memoryProperties_.memoryTypeCount && backing == UINT32_MAX; ++t)
    if ((memoryProperties_.memoryTypes[t].propertyFlags & host) == host) backing = t;
  if (backing == UINT32_MAX) throw Error("cannot pretend a discrete GPU: the device has no host-visible memory");
  const VkDeviceSize size = memoryProperties_.memoryHeaps[memoryProperties_.memoryTypes[backing].heapIndex].size;
  VkPhysicalDeviceMemoryProperties view{};
  view.memoryHeapCount = 3;
  view.memoryHeaps[0] = {size, VK_MEMORY_HEAP_DEVICE_LOCAL_BIT};                    // VRAM
  view.memoryHeaps[1] = {std::min(size, barBytes), VK_MEMORY_HEAP_DEVICE_LOCAL_BIT};  // its BAR window
  view.memoryHeaps[2] = {size, 0};                                                  // system memory
  view.memoryTypeCount = 4;  // in the order such drivers list them
  view.memoryTypes[0] = {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, 0};
  view.memoryTypes[1] = {host, 2};
  view.memoryTypes[2] = {host | VK_MEMORY_PROPERTY_HOST_CACHED_BIT, 2};
  view.memoryTypes[3] = {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | host, 1};
  memoryProperties_ = view;
  allocationTypes_.fill(backing);
  info_.deviceLocalBytes = size;
}

uint32_t Context::findMemoryType(uint32_t allowedTypes, VkMemoryPropertyFlags required,
                                 VkMemoryPropertyFlags preferred) const {
  uint32_t fallback = UINT32_MAX;
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    if (!(allowedTypes & (1u << allocationTypes_[i]))) continue;
    const VkMemoryPropertyFlags flags = memoryProperties_.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback == UINT32_MAX) fallback = i;
  }
  return fallback;
}

uint32_t Context::findDeviceMemoryType(uint32_t allowedTypes) const {
  const VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  uint32_t largestHeap = UINT32_MAX;
  for (uint32_t h = 0; h < memoryProperties_.memoryHeapCount; ++h)
    if ((memoryProperties_.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) &&
        (largestHeap == UINT32_MAX || memoryProperties_.memoryHeaps[h].size > memoryProperties_.memoryHeaps[largestHeap].size))
      largestHeap = h;
  uint32_t deviceOnly = UINT32_MAX;
  for (uint32_t i = 0; i < memoryProperties_.memoryTypeCount; ++i) {
    if (!(allowedTypes & (1u << allocationTypes_[i]))) continue;
    const VkMemoryType& type = memoryProperties_.memoryTypes[i];
    if (!(type.propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) continue;
    if ((type.propertyFlags & host) == host) {
      if (type.heapIndex == largestHeap) return i;  // mappable and large: no staging copies
    } else if (deviceOnly == UINT32_MAX) {
      deviceOnly = i;
    }
  }
  if (deviceOnly != UINT32_MAX) return deviceOnly;
  return findMemoryType(allowedTypes, 0);
}

void Context::submitAndWait(VkCommandBuffer commandBuffer) const {
  ++hostWaits_;
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkCreateFence(device_, &fenceInfo, nullptr, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commandBuffer;
  VkResult result = vkQueueSubmit(queue_, 1, &submit, fence);
  if (result == VK_SUCCESS) result = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
  vkDestroyFence(device_, fence, nullptr);
  HMB_VK_CHECK(result);
}

void Context::submitAndWait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = commandPool_;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer commandBuffer = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkAllocateCommandBuffers(device_, &allocInfo, &commandBuffer));
  // Freed on every path, a throwing record callback included.
  struct Release {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer buffer;
    ~Release() { vkFreeCommandBuffers(device, pool, 1, &buffer); }
  } release{device_, commandPool_, commandBuffer};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  HMB_VK_CHECK(vkBeginCommandBuffer(commandBuffer, &begin));
  record(commandBuffer);
  HMB_VK_CHECK(vkEndCommandBuffer(commandBuffer));
  submitAndWait(commandBuffer);
}

std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(messagesMutex_);
  return messages_;
}

VKAPI_ATTR VkBool32 VKAPI_CALL Context::onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                       VkDebugUtilsMessageTypeFlagsEXT,
                                                       const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                       void* user) {
  auto* self = static_cast<Context*>(user);
  const bool isError = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  (isError ? self->validationErrors_ : self->validationWarnings_).fetch_add(1);
  std::lock_guard lock(self->messagesMutex_);
  if (self->messages_.size() < kMaxKeptMessages)
    self->messages_.push_back(std::string(isError ? "error: " : "warning: ") +
                              (data && data->pMessage ? data->pMessage : "(no message)"));
  return VK_FALSE;
}

uint64_t Context::memoryInUse() const {
  uint64_t total = 0;
  for (const auto& heap : heapInUse_) total += heap.load();
  return total;
}

void Context::countRelease(uint32_t heap, uint64_t bytes) const { heapInUse_.at(heap).fetch_sub(bytes); }

void Context::countAllocation(uint32_t heap, uint64_t bytes) const {
  heapInUse_.at(heap).fetch_add(bytes);
  const uint64_t now = memoryInUse();
  uint64_t peak = memoryPeak_.load();
  while (now > peak && !memoryPeak_.compare_exchange_weak(peak, now)) {
  }
}

}  // namespace hmb::vk
