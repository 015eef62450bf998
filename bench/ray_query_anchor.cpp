#include "bench/ray_query_anchor.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include <vulkan/vulkan.h>

#include "bench/shaders/ray_query_layout.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "ray_query_trace.spv.h"
#include "runtime/vulkan/check.h"

namespace hmb::bench {
namespace {

constexpr const char* kExtensions[] = {VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME, VK_KHR_RAY_QUERY_EXTENSION_NAME,
                                       VK_KHR_DEFERRED_HOST_OPERATIONS_EXTENSION_NAME};
constexpr uint32_t kGroup = HMB_RAY_QUERY_GROUP;

// The features the anchor needs, chained for a query or for device creation.
struct FeatureChain {
  VkPhysicalDeviceBufferDeviceAddressFeatures addresses{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_BUFFER_DEVICE_ADDRESS_FEATURES};
  VkPhysicalDeviceAccelerationStructureFeaturesKHR structures{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_FEATURES_KHR};
  VkPhysicalDeviceRayQueryFeaturesKHR rayQuery{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RAY_QUERY_FEATURES_KHR};
  VkPhysicalDeviceFeatures2 features2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  FeatureChain() {
    features2.pNext = &addresses;
    addresses.pNext = &structures;
    structures.pNext = &rayQuery;
  }
  FeatureChain(const FeatureChain&) = delete;
};

bool hasExtension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

// One buffer with its own memory and device address; mapped when host-visible was asked for.
struct AnchorBuffer {
  VkDevice device = VK_NULL_HANDLE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceAddress address = 0;
  void* mapped = nullptr;

  AnchorBuffer() = default;
  AnchorBuffer(const AnchorBuffer&) = delete;
  AnchorBuffer& operator=(const AnchorBuffer&) = delete;
  ~AnchorBuffer() { release(); }
  void release() {
    if (!device) return;
    if (buffer) vkDestroyBuffer(device, buffer, nullptr);
    if (memory) vkFreeMemory(device, memory, nullptr);
    buffer = VK_NULL_HANDLE;
    memory = VK_NULL_HANDLE;
    mapped = nullptr;
    address = 0;
  }
};

}  // namespace

struct RayQueryAnchor::State {
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkQueryPool timestamps = VK_NULL_HANDLE;
  double nsPerTick = 1.0;
  uint64_t timestampMask = ~uint64_t{0};
  VkPhysicalDeviceMemoryProperties memory{};
  VkDeviceSize scratchAlignment = 1;

  PFN_vkCreateAccelerationStructureKHR createStructure = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroyStructure = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR buildSizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR cmdBuild = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR structureAddress = nullptr;

  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;

  // The last build: inputs, the two structures and their storage.
  AnchorBuffer vertices, indices, instance, bottomStorage, topStorage;
  VkAccelerationStructureKHR bottom = VK_NULL_HANDLE, top = VK_NULL_HANDLE;

  ~State() {
    if (!device) return;
    vkDeviceWaitIdle(device);
    releaseBuild();
    if (descriptorPool) vkDestroyDescriptorPool(device, descriptorPool, nullptr);
    if (pipeline) vkDestroyPipeline(device, pipeline, nullptr);
    if (pipelineLayout) vkDestroyPipelineLayout(device, pipelineLayout, nullptr);
    if (setLayout) vkDestroyDescriptorSetLayout(device, setLayout, nullptr);
    if (timestamps) vkDestroyQueryPool(device, timestamps, nullptr);
    if (fence) vkDestroyFence(device, fence, nullptr);
    if (pool) vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyDevice(device, nullptr);
  }

  void releaseBuild() {
    if (top) destroyStructure(device, top, nullptr);
    if (bottom) destroyStructure(device, bottom, nullptr);
    top = bottom = VK_NULL_HANDLE;
    for (AnchorBuffer* b : {&vertices, &indices, &instance, &bottomStorage, &topStorage}) b->release();
  }

  uint32_t memoryType(uint32_t allowed, VkMemoryPropertyFlags required, VkMemoryPropertyFlags preferred) const {
    uint32_t fallback = UINT32_MAX;
    for (uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      const VkMemoryPropertyFlags flags = memory.memoryTypes[i].propertyFlags;
      if (!(allowed & (1u << i)) || (flags & required) != required) continue;
      if ((flags & preferred) == preferred) return i;
      if (fallback == UINT32_MAX) fallback = i;
    }
    return fallback;
  }

  // Inputs and outputs the host reads or writes are host-visible; the structures and their
  // scratch prefer device-local memory.
  void allocate(AnchorBuffer& out, VkDeviceSize bytes, VkBufferUsageFlags usage, bool hostVisible) {
    out.release();
    out.device = device;
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = std::max<VkDeviceSize>(bytes, 16);
    info.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    HMB_VK_CHECK(vkCreateBuffer(device, &info, nullptr, &out.buffer));
    VkMemoryRequirements requirements;
    vkGetBufferMemoryRequirements(device, out.buffer, &requirements);
    const VkMemoryPropertyFlags required =
        hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT : 0;
    const uint32_t type = memoryType(requirements.memoryTypeBits, required, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type == UINT32_MAX) throw Error("ray-query anchor: no memory type for a buffer");
    VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    allocation.pNext = &flags;
    allocation.allocationSize = requirements.size;
    allocation.memoryTypeIndex = type;
    HMB_VK_CHECK(vkAllocateMemory(device, &allocation, nullptr, &out.memory));
    HMB_VK_CHECK(vkBindBufferMemory(device, out.buffer, out.memory, 0));
    if (hostVisible) HMB_VK_CHECK(vkMapMemory(device, out.memory, 0, VK_WHOLE_SIZE, 0, &out.mapped));
    VkBufferDeviceAddressInfo addressInfo{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    addressInfo.buffer = out.buffer;
    out.address = vkGetBufferDeviceAddress(device, &addressInfo);
  }

  template <typename T>
  void upload(AnchorBuffer& out, std::span<const T> data, VkBufferUsageFlags usage) {
    allocate(out, data.size_bytes(), usage, true);
    if (!data.empty()) std::memcpy(out.mapped, data.data(), data.size_bytes());
  }

  // Records with `record` between two timestamps, submits, waits; the milliseconds between.
  template <typename Record>
  double timed(Record record) {
    HMB_VK_CHECK(vkResetCommandBuffer(commands, 0));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    HMB_VK_CHECK(vkBeginCommandBuffer(commands, &begin));
    vkCmdResetQueryPool(commands, timestamps, 0, 2);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, timestamps, 0);
    record(commands);
    vkCmdWriteTimestamp(commands, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, timestamps, 1);
    HMB_VK_CHECK(vkEndCommandBuffer(commands));
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands;
    HMB_VK_CHECK(vkResetFences(device, 1, &fence));
    HMB_VK_CHECK(vkQueueSubmit(queue, 1, &submit, fence));
    HMB_VK_CHECK(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX));
    uint64_t ticks[2] = {0, 0};
    HMB_VK_CHECK(vkGetQueryPoolResults(device, timestamps, 0, 2, sizeof(ticks), ticks, sizeof(uint64_t),
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    return double((ticks[1] - ticks[0]) & timestampMask) * nsPerTick * 1e-6;
  }

  // Creates a structure of `type` over `geometry` and records its build into `cb`.
  VkAccelerationStructureKHR recordBuild(VkCommandBuffer cb, VkAccelerationStructureTypeKHR type,
                                         const VkAccelerationStructureGeometryKHR& geometry, uint32_t primitives,
                                         AnchorBuffer& storage, AnchorBuffer& scratchBuffer) {
    VkAccelerationStructureBuildGeometryInfoKHR info{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
    info.type = type;
    info.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
    info.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
    info.geometryCount = 1;
    info.pGeometries = &geometry;
    VkAccelerationStructureBuildSizesInfoKHR sizes{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    buildSizes(device, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &info, &primitives, &sizes);
    allocate(storage, sizes.accelerationStructureSize, VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR, false);
    allocate(scratchBuffer, sizes.buildScratchSize + scratchAlignment, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, false);
    VkAccelerationStructureCreateInfoKHR create{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
    create.buffer = storage.buffer;
    create.size = sizes.accelerationStructureSize;
    create.type = type;
    VkAccelerationStructureKHR structure = VK_NULL_HANDLE;
    HMB_VK_CHECK(createStructure(device, &create, nullptr, &structure));
    info.dstAccelerationStructure = structure;
    info.scratchData.deviceAddress = (scratchBuffer.address + scratchAlignment - 1) / scratchAlignment * scratchAlignment;
    VkAccelerationStructureBuildRangeInfoKHR range{};
    range.primitiveCount = primitives;
    const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
    cmdBuild(cb, 1, &info, &ranges);
    return structure;
  }
};

std::string RayQueryAnchor::unavailableReason(const vk::Context& context) {
  const VkPhysicalDevice device = context.physicalDevice();
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(device, &props);
  if (props.apiVersion < VK_API_VERSION_1_2) return "the device is Vulkan " + context.info().apiVersion + ", not 1.2";
  for (const char* name : kExtensions)
    if (!hasExtension(device, name)) return std::string("the driver has no ") + name;
  FeatureChain chain;
  vkGetPhysicalDeviceFeatures2(device, &chain.features2);
  if (!chain.addresses.bufferDeviceAddress) return "the device has no bufferDeviceAddress";
  if (!chain.structures.accelerationStructure) return "the device has no accelerationStructure feature";
  if (!chain.rayQuery.rayQuery) return "the device has no rayQuery feature";
  if (!context.info().timestamps) return "the device's queue has no timestamps";
  return "";
}

RayQueryAnchor::RayQueryAnchor(const vk::Context& context) : state_(std::make_unique<State>()) {
  if (const std::string why = unavailableReason(context); !why.empty()) throw Error("ray-query anchor: " + why);
  State& s = *state_;
  s.physicalDevice = context.physicalDevice();
  s.nsPerTick = context.info().timestampPeriodNs;
  s.timestampMask = context.info().timestampMask;
  vkGetPhysicalDeviceMemoryProperties(s.physicalDevice, &s.memory);
  VkPhysicalDeviceAccelerationStructurePropertiesKHR structureProps{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &structureProps;
  vkGetPhysicalDeviceProperties2(s.physicalDevice, &props2);
  s.scratchAlignment = std::max<VkDeviceSize>(1, structureProps.minAccelerationStructureScratchOffsetAlignment);

  FeatureChain enabled;
  enabled.addresses.bufferDeviceAddress = VK_TRUE;
  enabled.structures.accelerationStructure = VK_TRUE;
  enabled.rayQuery.rayQuery = VK_TRUE;
  std::vector<const char*> extensions(std::begin(kExtensions), std::end(kExtensions));
  if (hasExtension(s.physicalDevice, "VK_KHR_portability_subset")) extensions.push_back("VK_KHR_portability_subset");
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = context.queueFamily();
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;
  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  deviceInfo.pNext = &enabled.features2;
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = static_cast<uint32_t>(extensions.size());
  deviceInfo.ppEnabledExtensionNames = extensions.data();
  HMB_VK_CHECK(vkCreateDevice(s.physicalDevice, &deviceInfo, nullptr, &s.device));
  vkGetDeviceQueue(s.device, context.queueFamily(), 0, &s.queue);

  const auto load = [&](auto& pointer, const char* name) {
    pointer = reinterpret_cast<std::remove_reference_t<decltype(pointer)>>(vkGetDeviceProcAddr(s.device, name));
    if (!pointer) throw Error(std::string("ray-query anchor: the driver does not give ") + name);
  };
  load(s.createStructure, "vkCreateAccelerationStructureKHR");
  load(s.destroyStructure, "vkDestroyAccelerationStructureKHR");
  load(s.buildSizes, "vkGetAccelerationStructureBuildSizesKHR");
  load(s.cmdBuild, "vkCmdBuildAccelerationStructuresKHR");
  load(s.structureAddress, "vkGetAccelerationStructureDeviceAddressKHR");

  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  poolInfo.queueFamilyIndex = context.queueFamily();
  HMB_VK_CHECK(vkCreateCommandPool(s.device, &poolInfo, nullptr, &s.pool));
  VkCommandBufferAllocateInfo commandInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  commandInfo.commandPool = s.pool;
  commandInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  commandInfo.commandBufferCount = 1;
  HMB_VK_CHECK(vkAllocateCommandBuffers(s.device, &commandInfo, &s.commands));
  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  HMB_VK_CHECK(vkCreateFence(s.device, &fenceInfo, nullptr, &s.fence));
  VkQueryPoolCreateInfo queryInfo{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  queryInfo.queryType = VK_QUERY_TYPE_TIMESTAMP;
  queryInfo.queryCount = 2;
  HMB_VK_CHECK(vkCreateQueryPool(s.device, &queryInfo, nullptr, &s.timestamps));

  const VkDescriptorSetLayoutBinding bindings[] = {
      {HMB_RAY_QUERY_BINDING_SCENE, VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {HMB_RAY_QUERY_BINDING_RAYS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {HMB_RAY_QUERY_BINDING_HITS, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.bindingCount = 3;
  setInfo.pBindings = bindings;
  HMB_VK_CHECK(vkCreateDescriptorSetLayout(s.device, &setInfo, nullptr, &s.setLayout));
  const VkPushConstantRange pushRange{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(uint32_t)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &s.setLayout;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &pushRange;
  HMB_VK_CHECK(vkCreatePipelineLayout(s.device, &layoutInfo, nullptr, &s.pipelineLayout));
  VkShaderModuleCreateInfo moduleInfo{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  moduleInfo.codeSize = sizeof(kSpv_ray_query_trace);
  moduleInfo.pCode = kSpv_ray_query_trace;
  VkShaderModule module = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkCreateShaderModule(s.device, &moduleInfo, nullptr, &module));
  VkComputePipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  pipelineInfo.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  pipelineInfo.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  pipelineInfo.stage.module = module;
  pipelineInfo.stage.pName = "main";
  pipelineInfo.layout = s.pipelineLayout;
  const VkResult created = vkCreateComputePipelines(s.device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &s.pipeline);
  vkDestroyShaderModule(s.device, module, nullptr);
  HMB_VK_CHECK(created);
  const VkDescriptorPoolSize poolSizes[] = {{VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR, 1},
                                            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 2}};
  VkDescriptorPoolCreateInfo descriptorPoolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  descriptorPoolInfo.maxSets = 1;
  descriptorPoolInfo.poolSizeCount = 2;
  descriptorPoolInfo.pPoolSizes = poolSizes;
  HMB_VK_CHECK(vkCreateDescriptorPool(s.device, &descriptorPoolInfo, nullptr, &s.descriptorPool));
  VkDescriptorSetAllocateInfo allocateInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  allocateInfo.descriptorPool = s.descriptorPool;
  allocateInfo.descriptorSetCount = 1;
  allocateInfo.pSetLayouts = &s.setLayout;
  HMB_VK_CHECK(vkAllocateDescriptorSets(s.device, &allocateInfo, &s.set));
}

RayQueryAnchor::~RayQueryAnchor() = default;

double RayQueryAnchor::build(const bvh::TriangleList& triangles) {
  State& s = *state_;
  HMB_VK_CHECK(vkDeviceWaitIdle(s.device));
  s.releaseBuild();
  const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
  s.upload(s.vertices, triangles.positions, input);
  s.upload(s.indices, triangles.indices, input);
  const uint32_t triangleCount = triangles.triangleCount();

  VkAccelerationStructureGeometryKHR mesh{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  mesh.geometryType = VK_GEOMETRY_TYPE_TRIANGLES_KHR;
  mesh.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
  VkAccelerationStructureGeometryTrianglesDataKHR& data = mesh.geometry.triangles;
  data.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_TRIANGLES_DATA_KHR;
  data.vertexFormat = VK_FORMAT_R32G32B32_SFLOAT;
  data.vertexData.deviceAddress = s.vertices.address;
  data.vertexStride = sizeof(glm::vec3);
  data.maxVertex = static_cast<uint32_t>(std::max<size_t>(triangles.positions.size(), 1) - 1);
  data.indexType = VK_INDEX_TYPE_UINT32;
  data.indexData.deviceAddress = s.indices.address;

  // The bottom level's address goes into the instance before the top level is recorded, so
  // the bottom level is created (not yet built) first: creation does not need the build.
  AnchorBuffer bottomScratch, topScratch;
  double milliseconds = s.timed([&](VkCommandBuffer cb) {
    s.bottom = s.recordBuild(cb, VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR, mesh, triangleCount,
                             s.bottomStorage, bottomScratch);
    VkAccelerationStructureDeviceAddressInfoKHR addressInfo{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    addressInfo.accelerationStructure = s.bottom;
    VkAccelerationStructureInstanceKHR instance{};
    instance.transform.matrix[0][0] = instance.transform.matrix[1][1] = instance.transform.matrix[2][2] = 1.0f;
    instance.mask = 0xff;
    instance.flags = VK_GEOMETRY_INSTANCE_TRIANGLE_FACING_CULL_DISABLE_BIT_KHR;
    instance.accelerationStructureReference = s.structureAddress(s.device, &addressInfo);
    s.upload(s.instance, std::span<const VkAccelerationStructureInstanceKHR>(&instance, 1), input);

    VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
    barrier.srcAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_WRITE_BIT_KHR;
    barrier.dstAccessMask = VK_ACCESS_ACCELERATION_STRUCTURE_READ_BIT_KHR;
    vkCmdPipelineBarrier(cb, VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
                         VK_PIPELINE_STAGE_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, 0, 1, &barrier, 0, nullptr, 0,
                         nullptr);
    VkAccelerationStructureGeometryKHR instances{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
    instances.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
    instances.flags = VK_GEOMETRY_OPAQUE_BIT_KHR;
    instances.geometry.instances.sType = VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR;
    instances.geometry.instances.data.deviceAddress = s.instance.address;
    s.top = s.recordBuild(cb, VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR, instances, 1, s.topStorage, topScratch);
  });
  return milliseconds;
}

double RayQueryAnchor::trace(std::span<const bvh::Ray> rays, std::vector<gpu::BvhHit>& hits) {
  State& s = *state_;
  if (!s.top) throw Error("ray-query anchor: trace before build");
  struct AnchorRay {
    glm::vec4 originTMin, directionTMax;
  };
  struct AnchorHit {
    float t, u, v;
    uint32_t triangle;
  };
  std::vector<AnchorRay> anchorRays;
  anchorRays.reserve(rays.size());
  // Ray queries take finite distances only.
  for (const bvh::Ray& r : rays)
    anchorRays.push_back({glm::vec4(r.origin, r.tMin), glm::vec4(r.direction, std::isfinite(r.tMax) ? r.tMax : FLT_MAX)});
  AnchorBuffer rayBuffer, hitBuffer;
  s.upload(rayBuffer, std::span<const AnchorRay>(anchorRays), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  s.allocate(hitBuffer, rays.size() * sizeof(AnchorHit), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);

  VkWriteDescriptorSetAccelerationStructureKHR structureWrite{
      VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET_ACCELERATION_STRUCTURE_KHR};
  structureWrite.accelerationStructureCount = 1;
  structureWrite.pAccelerationStructures = &s.top;
  const VkDescriptorBufferInfo rayInfo{rayBuffer.buffer, 0, VK_WHOLE_SIZE}, hitInfo{hitBuffer.buffer, 0, VK_WHOLE_SIZE};
  VkWriteDescriptorSet writes[3] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                    {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
  writes[0].pNext = &structureWrite;
  writes[0].dstBinding = HMB_RAY_QUERY_BINDING_SCENE;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_ACCELERATION_STRUCTURE_KHR;
  writes[1].dstBinding = HMB_RAY_QUERY_BINDING_RAYS;
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[1].pBufferInfo = &rayInfo;
  writes[2].dstBinding = HMB_RAY_QUERY_BINDING_HITS;
  writes[2].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  writes[2].pBufferInfo = &hitInfo;
  for (VkWriteDescriptorSet& write : writes) {
    write.dstSet = s.set;
    write.descriptorCount = 1;
  }
  HMB_VK_CHECK(vkDeviceWaitIdle(s.device));
  vkUpdateDescriptorSets(s.device, 3, writes, 0, nullptr);

  const auto count = static_cast<uint32_t>(rays.size());
  const uint32_t groups = (count + kGroup - 1) / kGroup;
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(s.physicalDevice, &props);
  if (groups > props.limits.maxComputeWorkGroupCount[0])
    throw Error("ray-query anchor: " + std::to_string(count) + " rays are more than one dispatch takes");
  const double milliseconds = s.timed([&](VkCommandBuffer cb) {
    vkCmdBindPipeline(cb, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipeline);
    vkCmdBindDescriptorSets(cb, VK_PIPELINE_BIND_POINT_COMPUTE, s.pipelineLayout, 0, 1, &s.set, 0, nullptr);
    vkCmdPushConstants(cb, s.pipelineLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(count), &count);
    if (groups > 0) vkCmdDispatch(cb, groups, 1, 1);
  });

  const auto* out = static_cast<const AnchorHit*>(hitBuffer.mapped);
  hits.assign(rays.size(), gpu::BvhHit{});
  for (size_t i = 0; i < rays.size(); ++i) {
    gpu::BvhHit& h = hits[i];
    const bool hit = out[i].triangle != HMB_NO_HIT;
    h.t = hit ? out[i].t : rays[i].tMax;
    h.u = out[i].u;
    h.v = out[i].v;
    h.triangle = hit ? out[i].triangle : HMB_NO_HIT;
    h.objectId = hit ? 0u : HMB_NO_HIT;
    h.instance = hit ? 0u : HMB_NO_HIT;
    h.entry = HMB_NO_HIT;
  }
  return milliseconds;
}

}  // namespace hmb::bench
