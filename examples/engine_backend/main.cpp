// A small engine that owns its Vulkan instance, device and frame, draws its own G-buffer with a
// graphics pipeline, and hands the G-buffer to hybrid-mblur to blur, frame by frame, through
// the public API alone (<hmblur/hmblur.h>): an adopted context, and hmb::EngineHybridMotionBlur
// (or hmb::EngineMotionBlur with --method postprocess) recorded into the engine's own command
// buffer, reading the G-buffer's attachments in place and writing the blurred frame into the
// engine's output image (no copies). Its attachments are 32-bit (camera-space depth in an R32F
// target), so that its frames compare with the command line's; the library reads the formats
// engines draw as well (RGBA16F, D32 depth as z/w, RG16F, octahedral normals: EngineGBufferImages).
// Each frame is written as OUT_DIR/frame-NN.png, with the sharp G-buffer colour beside it as
// OUT_DIR/frame-NN-sharp.png.
//  - By default it draws boxes (one sliding fast over a floor, one turning, one still under a
//    still camera), gives their geometry to the library as an hmb::EngineScene (the box mesh
//    once, each frame's world transforms now and one frame earlier), and shades what the rays
//    reveal with its own shadeHit.
//  - With --scene it draws a scene the library loads (a reference scene name or a glTF file)
//    with its own pipeline and the library's camera, base colours only (no textures), and the
//    library traces that scene, shading with the library's function: its frames then equal the
//    command line's wherever the two G-buffers agree.
//
// Usage: engine_backend [--validation] [--method hybrid|postprocess] [--scene SCENE] [--frames N]
//                       [--size WIDTHxHEIGHT] OUT_DIR
//   --validation: the Khronos validation layer with synchronization validation on the engine's
//   instance; any message it reports makes the exit code 3.
// Each frame prints the library's device times (EngineMotionBlur::timings): its passes, each
// named once with how often it ran, adding up to the frame, from the end of the engine's draws.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <hmblur/hmblur.h>
#include <vulkan/vulkan.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

#include "gbuffer_frag.spv.h"
#include "gbuffer_vert.spv.h"

namespace {

void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed (VkResult " + std::to_string(result) + ")");
}

constexpr float kFps = 60.0f;
constexpr VkFormat kColorFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kDepthOutFormat = VK_FORMAT_R32_SFLOAT;
constexpr VkFormat kVelocityFormat = VK_FORMAT_R32G32_SFLOAT;
constexpr VkFormat kNormalFormat = VK_FORMAT_R32G32B32A32_SFLOAT;
constexpr VkFormat kObjectIdFormat = VK_FORMAT_R32_UINT;
constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
constexpr uint32_t kColorTargets = 5;  // colour, depth, velocity, normal, object id

struct Vertex {
  glm::vec3 position, normal;
};

// What the shaders read per object (a storage buffer indexed by the draw's first instance).
struct ObjectData {
  glm::mat4 clipNow, clipPrevious, normalToWorld;
  glm::vec4 albedo;  // w: the object's id (the scene's Instance::objectId)
  glm::vec4 ambient, lightColor, lightDirection;
};

struct Mesh {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
};

Mesh boxMesh() {
  Mesh m;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    const glm::vec3 u = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 v = glm::cross(n, u);
    const auto base = static_cast<uint32_t>(m.vertices.size());
    for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
      m.vertices.push_back({0.5f * (n + c.x * u + c.y * v), n});
    // Wound so the face is counter-clockwise seen from outside, whatever the basis' handedness.
    const glm::vec3 e1 = m.vertices[base + 1].position - m.vertices[base].position;
    const glm::vec3 e2 = m.vertices[base + 2].position - m.vertices[base].position;
    if (glm::dot(glm::cross(e1, e2), n) > 0)
      m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    else
      m.indices.insert(m.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
  }
  return m;
}

// The engine's own Vulkan: instance (with validation when asked), device, one queue that does
// graphics and compute, a command pool.
struct Engine {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  VkCommandPool pool = VK_NULL_HANDLE;
  bool validation = false;
  uint32_t messages = 0;

  explicit Engine(bool withValidation) : validation(withValidation) {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "engine_backend";
    app.apiVersion = VK_API_VERSION_1_2;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (validation) {
      info.pNext = &features;
      info.enabledLayerCount = 1;
      info.ppEnabledLayerNames = &layer;
      info.enabledExtensionCount = 1;
      info.ppEnabledExtensionNames = &extension;
    }
    check(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
    if (validation) {
      VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
      m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
      m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                      VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
      m.pfnUserCallback = [](VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) -> VkBool32 {
        ++static_cast<Engine*>(user)->messages;
        std::fprintf(stderr, "engine_backend: validation: %s\n", data->pMessage ? data->pMessage : "");
        return VK_FALSE;
      };
      m.pUserData = this;
      auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
      check(create(instance, &m, nullptr, &messenger), "vkCreateDebugUtilsMessengerEXT");
    }
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance, &count, devices.data());
    for (VkPhysicalDevice candidate : devices) {
      uint32_t families = 0;
      vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, nullptr);
      std::vector<VkQueueFamilyProperties> properties(families);
      vkGetPhysicalDeviceQueueFamilyProperties(candidate, &families, properties.data());
      for (uint32_t f = 0; f < families && !physicalDevice; ++f)
        if ((properties[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (properties[f].queueFlags & VK_QUEUE_COMPUTE_BIT)) {
          physicalDevice = candidate;
          family = f;
        }
    }
    if (!physicalDevice) throw std::runtime_error("no device with a graphics and compute queue");
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queueInfo.queueFamilyIndex = family;
    queueInfo.queueCount = 1;
    queueInfo.pQueuePriorities = &priority;
    VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    deviceInfo.queueCreateInfoCount = 1;
    deviceInfo.pQueueCreateInfos = &queueInfo;
    check(vkCreateDevice(physicalDevice, &deviceInfo, nullptr, &device), "vkCreateDevice");
    vkGetDeviceQueue(device, family, 0, &queue);
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = family;
    check(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool");
  }

  ~Engine() {
    vkDestroyCommandPool(device, pool, nullptr);
    vkDestroyDevice(device, nullptr);
    if (messenger) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      destroy(instance, messenger, nullptr);
    }
    vkDestroyInstance(instance, nullptr);
  }

  // The library works on this device, using none of the optional features (none enabled).
  hmb::EngineVulkan adopted() const {
    hmb::EngineVulkan a;
    a.instance = instance;
    a.apiVersion = VK_API_VERSION_1_2;
    a.debugUtils = validation;
    a.physicalDevice = physicalDevice;
    a.device = device;
    a.queueFamily = family;
    return a;
  }

  uint32_t memoryType(uint32_t allowed, VkMemoryPropertyFlags wanted) const {
    VkPhysicalDeviceMemoryProperties memory{};
    vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memory);
    for (uint32_t t = 0; t < memory.memoryTypeCount; ++t)
      if ((allowed >> t & 1u) && (memory.memoryTypes[t].propertyFlags & wanted) == wanted) return t;
    throw std::runtime_error("no memory type with the wanted properties");
  }
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // host-visible buffers are mapped for their lifetime
};

Buffer makeBuffer(const Engine& e, VkDeviceSize size, VkBufferUsageFlags usage, bool hostVisible) {
  Buffer b;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  check(vkCreateBuffer(e.device, &info, nullptr, &b.buffer), "vkCreateBuffer");
  VkMemoryRequirements needs{};
  vkGetBufferMemoryRequirements(e.device, b.buffer, &needs);
  VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocation.allocationSize = needs.size;
  allocation.memoryTypeIndex = e.memoryType(
      needs.memoryTypeBits, hostVisible ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
                                        : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkAllocateMemory(e.device, &allocation, nullptr, &b.memory), "vkAllocateMemory");
  check(vkBindBufferMemory(e.device, b.buffer, b.memory, 0), "vkBindBufferMemory");
  if (hostVisible) check(vkMapMemory(e.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
  return b;
}

void destroy(const Engine& e, Buffer& b) {
  vkDestroyBuffer(e.device, b.buffer, nullptr);
  vkFreeMemory(e.device, b.memory, nullptr);
  b = {};
}

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

Image makeImage(const Engine& e, uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                VkImageAspectFlags aspect) {
  Image i;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  check(vkCreateImage(e.device, &info, nullptr, &i.image), "vkCreateImage");
  VkMemoryRequirements needs{};
  vkGetImageMemoryRequirements(e.device, i.image, &needs);
  VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocation.allocationSize = needs.size;
  allocation.memoryTypeIndex = e.memoryType(needs.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  check(vkAllocateMemory(e.device, &allocation, nullptr, &i.memory), "vkAllocateMemory");
  check(vkBindImageMemory(e.device, i.image, i.memory, 0), "vkBindImageMemory");
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = i.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {aspect, 0, 1, 0, 1};
  check(vkCreateImageView(e.device, &view, nullptr, &i.view), "vkCreateImageView");
  return i;
}

void destroy(const Engine& e, Image& i) {
  vkDestroyImageView(e.device, i.view, nullptr);
  vkDestroyImage(e.device, i.image, nullptr);
  vkFreeMemory(e.device, i.memory, nullptr);
  i = {};
}

VkShaderModule shaderModule(const Engine& e, const uint32_t* code, size_t words) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = words * sizeof(uint32_t);
  info.pCode = code;
  VkShaderModule module = VK_NULL_HANDLE;
  check(vkCreateShaderModule(e.device, &info, nullptr, &module), "vkCreateShaderModule");
  return module;
}

// The G-buffer pass: five colour attachments (colour, camera-space depth, velocity, normal,
// object id) and a depth buffer; the colour attachments end ready for the library's compute
// passes to read them in place (the colour one also for the copy the example keeps of it).
struct GBufferPass {
  VkRenderPass renderPass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkPipeline culling = VK_NULL_HANDLE;  // single-sided materials: back faces culled (glTF)
  VkPipeline twoSided = VK_NULL_HANDLE;  // double-sided ones
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet set = VK_NULL_HANDLE;
  Image color, depthOut, velocity, normal, objectId, depth;

  GBufferPass(const Engine& e, uint32_t width, uint32_t height, VkBuffer objects) {
    const VkImageUsageFlags target = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                     VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    color = makeImage(e, width, height, kColorFormat, target, VK_IMAGE_ASPECT_COLOR_BIT);
    depthOut = makeImage(e, width, height, kDepthOutFormat, target, VK_IMAGE_ASPECT_COLOR_BIT);
    velocity = makeImage(e, width, height, kVelocityFormat, target, VK_IMAGE_ASPECT_COLOR_BIT);
    normal = makeImage(e, width, height, kNormalFormat, target, VK_IMAGE_ASPECT_COLOR_BIT);
    objectId = makeImage(e, width, height, kObjectIdFormat, target, VK_IMAGE_ASPECT_COLOR_BIT);
    depth = makeImage(e, width, height, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                      VK_IMAGE_ASPECT_DEPTH_BIT);

    std::array<VkAttachmentDescription, kColorTargets + 1> attachments{};
    const VkFormat formats[kColorTargets + 1] = {kColorFormat,  kDepthOutFormat, kVelocityFormat,
                                                 kNormalFormat, kObjectIdFormat, kDepthFormat};
    for (uint32_t a = 0; a <= kColorTargets; ++a) {
      attachments[a].format = formats[a];
      attachments[a].samples = VK_SAMPLE_COUNT_1_BIT;
      attachments[a].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
      attachments[a].storeOp = a < kColorTargets ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
      attachments[a].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
      attachments[a].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
      attachments[a].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
      attachments[a].finalLayout = a < kColorTargets ? VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL
                                                     : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    }
    VkAttachmentReference colorRefs[kColorTargets];
    for (uint32_t a = 0; a < kColorTargets; ++a) colorRefs[a] = {a, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference depthRef{kColorTargets, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = kColorTargets;
    subpass.pColorAttachments = colorRefs;
    subpass.pDepthStencilAttachment = &depthRef;
    // Before: the last frame's reads of the attachments (the library's, the colour's copy) and
    // its depth tests. After: this frame's reads of them.
    std::array<VkSubpassDependency, 2> dependencies{};
    dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[0].dstSubpass = 0;
    dependencies[0].srcStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                                   VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dependencies[0].dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    dependencies[0].srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[0].dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dependencies[1].srcSubpass = 0;
    dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
    dependencies[1].srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    dependencies[1].dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    dependencies[1].srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    dependencies[1].dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
    VkRenderPassCreateInfo passInfo{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    passInfo.attachmentCount = kColorTargets + 1;
    passInfo.pAttachments = attachments.data();
    passInfo.subpassCount = 1;
    passInfo.pSubpasses = &subpass;
    passInfo.dependencyCount = 2;
    passInfo.pDependencies = dependencies.data();
    check(vkCreateRenderPass(e.device, &passInfo, nullptr, &renderPass), "vkCreateRenderPass");
    const VkImageView views[kColorTargets + 1] = {color.view, depthOut.view, velocity.view,
                                                  normal.view, objectId.view, depth.view};
    VkFramebufferCreateInfo fb{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fb.renderPass = renderPass;
    fb.attachmentCount = kColorTargets + 1;
    fb.pAttachments = views;
    fb.width = width;
    fb.height = height;
    fb.layers = 1;
    check(vkCreateFramebuffer(e.device, &fb, nullptr, &framebuffer), "vkCreateFramebuffer");

    VkDescriptorSetLayoutBinding binding{0, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                                         VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
    VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    setInfo.bindingCount = 1;
    setInfo.pBindings = &binding;
    check(vkCreateDescriptorSetLayout(e.device, &setInfo, nullptr, &setLayout), "vkCreateDescriptorSetLayout");
    VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    layoutInfo.setLayoutCount = 1;
    layoutInfo.pSetLayouts = &setLayout;
    check(vkCreatePipelineLayout(e.device, &layoutInfo, nullptr, &layout), "vkCreatePipelineLayout");
    const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1};
    VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    poolInfo.maxSets = 1;
    poolInfo.poolSizeCount = 1;
    poolInfo.pPoolSizes = &size;
    check(vkCreateDescriptorPool(e.device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool");
    VkDescriptorSetAllocateInfo allocation{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    allocation.descriptorPool = pool;
    allocation.descriptorSetCount = 1;
    allocation.pSetLayouts = &setLayout;
    check(vkAllocateDescriptorSets(e.device, &allocation, &set), "vkAllocateDescriptorSets");
    const VkDescriptorBufferInfo bufferInfo{objects, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    write.dstSet = set;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &bufferInfo;
    vkUpdateDescriptorSets(e.device, 1, &write, 0, nullptr);

    const VkShaderModule vert = shaderModule(e, kSpvGbufferVert, sizeof(kSpvGbufferVert) / sizeof(uint32_t));
    const VkShaderModule frag = shaderModule(e, kSpvGbufferFrag, sizeof(kSpvGbufferFrag) / sizeof(uint32_t));
    const float viewport[2] = {float(width), float(height)};
    const VkSpecializationMapEntry entries[2] = {{0, 0, sizeof(float)}, {1, sizeof(float), sizeof(float)}};
    const VkSpecializationInfo specialization{2, entries, sizeof(viewport), viewport};
    VkPipelineShaderStageCreateInfo stages[2] = {{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO},
                                                 {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO}};
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    stages[1].pSpecializationInfo = &specialization;
    const VkVertexInputBindingDescription vertexBinding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
    const VkVertexInputAttributeDescription vertexAttributes[2] = {
        {0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
        {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)}};
    VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    vertexInput.vertexBindingDescriptionCount = 1;
    vertexInput.pVertexBindingDescriptions = &vertexBinding;
    vertexInput.vertexAttributeDescriptionCount = 2;
    vertexInput.pVertexAttributeDescriptions = vertexAttributes;
    VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    const VkViewport vp{0, 0, float(width), float(height), 0, 1};
    const VkRect2D scissor{{0, 0}, {width, height}};
    VkPipelineViewportStateCreateInfo viewportState{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    viewportState.viewportCount = 1;
    viewportState.pViewports = &vp;
    viewportState.scissorCount = 1;
    viewportState.pScissors = &scissor;
    VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    raster.polygonMode = VK_POLYGON_MODE_FILL;
    raster.cullMode = VK_CULL_MODE_BACK_BIT;
    // Counter-clockwise in glTF's y-up view; the projection's y flip keeps Vulkan's rule for it.
    raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    raster.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
    VkPipelineDepthStencilStateCreateInfo depthState{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    depthState.depthTestEnable = VK_TRUE;
    depthState.depthWriteEnable = VK_TRUE;
    depthState.depthCompareOp = VK_COMPARE_OP_GREATER;  // the library's projection: reversed depth
    std::array<VkPipelineColorBlendAttachmentState, kColorTargets> blend{};
    for (auto& b : blend) b.colorWriteMask = 0xf;
    VkPipelineColorBlendStateCreateInfo blendState{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    blendState.attachmentCount = kColorTargets;
    blendState.pAttachments = blend.data();
    VkGraphicsPipelineCreateInfo pipelineInfo{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    pipelineInfo.stageCount = 2;
    pipelineInfo.pStages = stages;
    pipelineInfo.pVertexInputState = &vertexInput;
    pipelineInfo.pInputAssemblyState = &assembly;
    pipelineInfo.pViewportState = &viewportState;
    pipelineInfo.pRasterizationState = &raster;
    pipelineInfo.pMultisampleState = &multisample;
    pipelineInfo.pDepthStencilState = &depthState;
    pipelineInfo.pColorBlendState = &blendState;
    pipelineInfo.layout = layout;
    pipelineInfo.renderPass = renderPass;
    check(vkCreateGraphicsPipelines(e.device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &culling),
          "vkCreateGraphicsPipelines");
    raster.cullMode = VK_CULL_MODE_NONE;
    check(vkCreateGraphicsPipelines(e.device, VK_NULL_HANDLE, 1, &pipelineInfo, nullptr, &twoSided),
          "vkCreateGraphicsPipelines");
    vkDestroyShaderModule(e.device, vert, nullptr);
    vkDestroyShaderModule(e.device, frag, nullptr);
  }

  void destroyWith(const Engine& e) {
    vkDestroyPipeline(e.device, culling, nullptr);
    vkDestroyPipeline(e.device, twoSided, nullptr);
    vkDestroyPipelineLayout(e.device, layout, nullptr);
    vkDestroyDescriptorPool(e.device, pool, nullptr);
    vkDestroyDescriptorSetLayout(e.device, setLayout, nullptr);
    vkDestroyFramebuffer(e.device, framebuffer, nullptr);
    vkDestroyRenderPass(e.device, renderPass, nullptr);
    for (Image* i : {&color, &depthOut, &velocity, &normal, &objectId, &depth}) destroy(e, *i);
  }
};

// The boxes, as the engine knows them: the floor, a box sliding fast, a box turning, a box
// still, each with its colour and object id, placed at time t (seconds).
struct Placement {
  glm::vec3 translation, scale;
  float turn;  // radians about +y
  glm::vec3 albedo;
  uint32_t objectId;
  glm::mat4 model() const {
    return glm::scale(glm::rotate(glm::translate(glm::mat4(1), translation), turn, {0, 1, 0}), scale);
  }
};

std::vector<Placement> placementsAt(float t) {
  return {{{0, -0.55f, 0}, {12, 0.1f, 12}, 0.0f, {0.55f, 0.55f, 0.5f}, 1},
          {{-2.5f + 15.0f * (t - 1.0f / 3.0f), 0, 0.8f}, {1, 1, 1}, 0.0f, {0.9f, 0.3f, 0.2f}, 2},  // 15 units a second
          {{1.2f, 0, -1.5f}, {1, 1, 1}, 20.0f * t, {0.2f, 0.5f, 0.9f}, 3},                         // 20 radians a second
          {{-1.6f, 0, -1.2f}, {1, 1, 1}, 0.0f, {0.3f, 0.8f, 0.3f}, 4}};
}

// The engine's sky, linear: its clear colour, and what the library's rays that hit nothing see.
constexpr glm::vec3 kSky{0.62f, 0.74f, 0.9f};

// The boxes' geometry for the library's rays (hmb::EngineScene): a box mesh per colour once,
// then per frame each box's world transform now and one frame earlier, and the still camera.
struct Boxes {
  hmb::EngineScene scene{kFps, 0.5f / kFps, 0.05f};  // a 180-degree shutter; SOFT_Z_EXTENT in scene units
  explicit Boxes(const Mesh& box) {
    std::vector<glm::vec3> positions, normals;
    for (const Vertex& v : box.vertices) {
      positions.push_back(v.position);
      normals.push_back(v.normal);
    }
    for (const Placement& p : placementsAt(0.0f)) scene.addMesh(positions, normals, box.indices, p.albedo);
    hmb::scene::DirectionalLight light;
    light.direction = -glm::normalize(glm::vec3(0.4f, 0.8f, 0.5f));
    light.color = glm::vec3(0.75f);
    light.ambient = glm::vec3(0.25f);
    scene.setLight(light);
    scene.setBackground(kSky);
    setFrame(1.0f / 3.0f + 1.0f / kFps);
  }
  void setFrame(float t) {
    const std::vector<Placement> now = placementsAt(t), before = placementsAt(t - 1.0f / kFps);
    std::vector<hmb::EngineScene::Instance> instances;
    for (uint32_t i = 0; i < now.size(); ++i) instances.push_back({i, now[i].objectId, now[i].model(), before[i].model()});
    const glm::mat4 camera = glm::inverse(glm::lookAt(glm::vec3(0, 2.2f, 5.5f), {0, 0, 0}, {0, 1, 0}));
    scene.setFrame(t, instances, {camera, camera, glm::radians(50.0f), 0.1f, 100.0f});
  }
};

// What the rays reveal of the boxes, lit by the engine's own shading function: the colour by
// object id (the engine's table, not the library's materials), the same light.
constexpr const char* kBoxesShadeHit = R"glsl(
vec3 shadeHit(HitRecord hit) {
  const vec3 albedo[5] = vec3[5](vec3(0.0), vec3(0.55, 0.55, 0.5), vec3(0.9, 0.3, 0.2), vec3(0.2, 0.5, 0.9),
                                 vec3(0.3, 0.8, 0.3));
  const vec3 light = normalize(vec3(0.4, 0.8, 0.5));
  return albedo[min(hit.objectId, 4u)] * (0.25 + 0.75 * max(dot(hit.normal, light), 0.0));
}
)glsl";

// Every mesh of a scene in one vertex and index buffer, and where each one's triangles start.
struct SceneGeometry {
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  struct Range {
    uint32_t firstIndex, indexCount;
    int32_t vertexOffset;
  };
  std::vector<Range> meshes;
  explicit SceneGeometry(const hmb::scene::Scene& scene) {
    for (const hmb::scene::Mesh& mesh : scene.meshes) {
      meshes.push_back({uint32_t(indices.size()), uint32_t(mesh.indices.size()), int32_t(vertices.size())});
      for (size_t i = 0; i < mesh.positions.size(); ++i) vertices.push_back({mesh.positions[i], mesh.normals[i]});
      indices.insert(indices.end(), mesh.indices.begin(), mesh.indices.end());
    }
  }
};

// Each instance of the scene at time t, for the shaders: the library's camera (its projection:
// Vulkan clip space, reversed depth), the scene's materials and light.
std::vector<ObjectData> objectsAt(const hmb::scene::Scene& scene, float t, uint32_t width, uint32_t height) {
  const hmb::FrameCamera camera = hmb::frameCamera(scene, t, width, height);
  const float before = t - 1.0f / scene.settings.fps;
  std::vector<ObjectData> objects;
  for (const hmb::scene::Instance& instance : scene.instances) {
    const glm::mat4 now = scene.worldMatrixAt(instance.node, t), then = scene.worldMatrixAt(instance.node, before);
    const hmb::scene::Material& material = scene.materials[scene.meshes[instance.mesh].material];
    objects.push_back({camera.viewProjCurrent * now, camera.viewProjPrevious * then, glm::transpose(glm::inverse(now)),
                       glm::vec4(glm::vec3(material.baseColorFactor), float(instance.objectId)),
                       glm::vec4(scene.light.ambient, 0.0f), glm::vec4(scene.light.color, 0.0f),
                       glm::vec4(scene.light.direction, 0.0f)});
  }
  return objects;
}

float srgb(float linear) {
  const float c = std::isfinite(linear) ? std::clamp(linear, 0.0f, 1.0f) : 0.0f;
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

void writePng(const std::filesystem::path& path, const float* rgba, uint32_t width, uint32_t height) {
  std::vector<uint8_t> pixels(size_t(width) * height * 4);
  for (size_t i = 0; i < size_t(width) * height; ++i) {
    for (int c = 0; c < 3; ++c) pixels[4 * i + c] = static_cast<uint8_t>(std::lround(255.0f * srgb(rgba[4 * i + c])));
    pixels[4 * i + 3] = 255;
  }
  if (!stbi_write_png(path.string().c_str(), int(width), int(height), 4, pixels.data(), int(width) * 4))
    throw std::runtime_error("could not write " + path.string());
}

}  // namespace

constexpr const char* kUsage =
    "usage: engine_backend [--validation] [--method hybrid|hybrid-rays|postprocess] [--scene SCENE] [--frames N]\n"
    "                      [--size WIDTHxHEIGHT] OUT_DIR\n";

int main(int argc, char** argv) {
  bool validation = false;
  bool hybrid = true;
  bool shutterRays = false;  // hybrid-rays: the paper's blur with shutter rays at edges
  int frames = 4;
  uint32_t width = 640, height = 360;
  std::string sceneName;  // empty: the boxes
  std::filesystem::path outDir;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--validation") validation = true;
    else if (arg == "--frames" && a + 1 < argc) frames = std::clamp(std::atoi(argv[++a]), 1, 60);
    else if (arg == "--scene" && a + 1 < argc) sceneName = argv[++a];
    else if (arg == "--method" && a + 1 < argc) {
      const std::string method = argv[++a];
      if (method != "hybrid" && method != "hybrid-rays" && method != "postprocess") {
        std::fprintf(stderr, "engine_backend: --method takes hybrid, hybrid-rays or postprocess\n");
        return 2;
      }
      hybrid = method != "postprocess";
      shutterRays = method == "hybrid-rays";
    } else if (arg == "--size" && a + 1 < argc) {
      if (std::sscanf(argv[++a], "%ux%u", &width, &height) != 2 || width == 0 || height == 0 || width > 8192 ||
          height > 8192) {
        std::fprintf(stderr, "engine_backend: --size takes WIDTHxHEIGHT, 1 to 8192 each\n");
        return 2;
      }
    } else if (outDir.empty() && arg[0] != '-') outDir = arg;
    else {
      std::fprintf(stderr, "%s", kUsage);
      return 2;
    }
  }
  if (outDir.empty()) {
    std::fprintf(stderr, "%s", kUsage);
    return 2;
  }
  try {
    std::filesystem::create_directories(outDir);
    // What the engine draws: the boxes, or a scene the library loads (the engine draws it with
    // its own pipeline; the library traces it for the hybrid's reveal).
    const Mesh box = boxMesh();
    std::unique_ptr<Boxes> boxes;
    hmb::scene::Scene loaded;
    if (sceneName.empty()) {
      boxes = std::make_unique<Boxes>(box);
    } else {
      loaded = hmb::scene::loadScene(sceneName);
      if (loaded.hasDeformation()) throw std::runtime_error("this example draws rigid meshes only: " + sceneName + " deforms");
      for (const hmb::scene::Material& m : loaded.materials)
        if (m.baseColorTexture >= 0) {
          std::fprintf(stderr, "engine_backend: warning: textures are not drawn by this example (base colours only)\n");
          break;
        }
    }
    const hmb::scene::Scene& scene = boxes ? boxes->scene.scene() : loaded;
    const float firstTime = boxes ? 1.0f / 3.0f + 1.0f / kFps : loaded.settings.frameTime;
    const float fps = scene.settings.fps;

    Engine engine(validation);
    const size_t pixels = size_t(width) * height;
    // The library writes the blurred frame into the engine's output image; the example copies it
    // and the sharp colour into buffers the host reads, to write its PNGs.
    Image output = makeImage(engine, width, height, kColorFormat,
                             VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    Buffer blurred = makeBuffer(engine, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    Buffer sharp = makeBuffer(engine, pixels * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT, true);
    const SceneGeometry geometry(scene);
    Buffer vertices =
        makeBuffer(engine, geometry.vertices.size() * sizeof(Vertex), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, true);
    Buffer indices = makeBuffer(engine, geometry.indices.size() * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT, true);
    std::memcpy(vertices.mapped, geometry.vertices.data(), geometry.vertices.size() * sizeof(Vertex));
    std::memcpy(indices.mapped, geometry.indices.data(), geometry.indices.size() * 4);
    const auto objectCount = static_cast<uint32_t>(scene.instances.size());
    Buffer objects = makeBuffer(engine, std::max<size_t>(objectCount, 1) * sizeof(ObjectData),
                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, true);
    GBufferPass gbuffer(engine, width, height, objects.buffer);

    {
      hmb::EngineContextOptions options;
      options.validation = validation;  // the library's messages are counted too
      hmb::EngineContext context(engine.adopted(), options);
      // The blur's settings as the renderer derives them for this scene and image.
      const hmb::EngineHybridSettings settings = hmb::engineHybridSettingsFor(scene, width, height, shutterRays);
      const hmb::EngineShading shading(boxes ? kBoxesShadeHit : "");  // a loaded scene: the library's
      std::unique_ptr<hmb::EngineMotionBlur> postProcess;
      std::unique_ptr<hmb::EngineHybridMotionBlur> hybridBlur;
      if (hybrid)
        hybridBlur = std::make_unique<hmb::EngineHybridMotionBlur>(context, width, height, scene, settings,
                                                                   hmb::EngineDepth{}, &shading);
      else
        postProcess = std::make_unique<hmb::EngineMotionBlur>(context, width, height,
                                                              hmb::engineBlurSettingsFor(scene, width, height));

      VkCommandBufferAllocateInfo allocation{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      allocation.commandPool = engine.pool;
      allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      allocation.commandBufferCount = 1;
      VkCommandBuffer commands = VK_NULL_HANDLE;
      check(vkAllocateCommandBuffers(engine.device, &allocation, &commands), "vkAllocateCommandBuffers");
      VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      VkFence fence = VK_NULL_HANDLE;
      check(vkCreateFence(engine.device, &fenceInfo, nullptr, &fence), "vkCreateFence");

      for (int f = 0; f < frames; ++f) {
        const float t = firstTime + float(f) / fps;
        if (boxes) boxes->setFrame(t);
        const std::vector<ObjectData> data = objectsAt(scene, t, width, height);
        std::memcpy(objects.mapped, data.data(), data.size() * sizeof(ObjectData));
        // The hybrid's trees for this frame's instances (it waits for them), before recording.
        if (hybridBlur) hybridBlur->prepare(t);

        check(vkResetCommandBuffer(commands, 0), "vkResetCommandBuffer");
        VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
        begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
        check(vkBeginCommandBuffer(commands, &begin), "vkBeginCommandBuffer");
        // The engine's own frame: the G-buffer pass ...
        VkClearValue clears[kColorTargets + 1] = {};
        clears[0].color = boxes ? VkClearColorValue{{kSky.r, kSky.g, kSky.b, 1.0f}}
                                : VkClearColorValue{{0.0f, 0.0f, 0.0f, 1.0f}};  // a loaded scene's background
        clears[1].color = {{0.0f, 0, 0, 0}};  // depth 0: nothing there (the background)
        clears[2].color = {{0.0f, 0, 0, 0}};  // the background does not move on screen: the camera is still
        clears[3].color = {{0.0f, 0, 0, 0}};  // no normal
        clears[4].color.uint32[0] = 0;        // object 0: the background
        clears[kColorTargets].depthStencil = {0.0f, 0};  // reversed depth: 0 is the far plane
        VkRenderPassBeginInfo passBegin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
        passBegin.renderPass = gbuffer.renderPass;
        passBegin.framebuffer = gbuffer.framebuffer;
        passBegin.renderArea = {{0, 0}, {width, height}};
        passBegin.clearValueCount = kColorTargets + 1;
        passBegin.pClearValues = clears;
        vkCmdBeginRenderPass(commands, &passBegin, VK_SUBPASS_CONTENTS_INLINE);
        vkCmdBindDescriptorSets(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, gbuffer.layout, 0, 1, &gbuffer.set, 0, nullptr);
        const VkDeviceSize offset = 0;
        vkCmdBindVertexBuffers(commands, 0, 1, &vertices.buffer, &offset);
        vkCmdBindIndexBuffer(commands, indices.buffer, 0, VK_INDEX_TYPE_UINT32);
        for (uint32_t o = 0; o < objectCount; ++o) {  // instance o: object o
          const hmb::scene::Mesh& mesh = scene.meshes[scene.instances[o].mesh];
          const bool doubleSided = scene.materials[mesh.material].doubleSided;
          vkCmdBindPipeline(commands, VK_PIPELINE_BIND_POINT_GRAPHICS, doubleSided ? gbuffer.twoSided : gbuffer.culling);
          const SceneGeometry::Range& range = geometry.meshes[scene.instances[o].mesh];
          vkCmdDrawIndexed(commands, range.indexCount, 1, range.firstIndex, range.vertexOffset, o);
        }
        vkCmdEndRenderPass(commands);
        // ... the output image made writable (after the last frame's copy out of it; its old
        // contents go) ...
        VkImageMemoryBarrier toGeneral{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        toGeneral.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        toGeneral.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        toGeneral.newLayout = VK_IMAGE_LAYOUT_GENERAL;
        toGeneral.srcQueueFamilyIndex = toGeneral.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        toGeneral.image = output.image;
        toGeneral.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0,
                             nullptr, 0, nullptr, 1, &toGeneral);
        // ... the G-buffer's attachments blurred by the library where they are, in this command
        // buffer, into the output image ...
        const hmb::EngineGBufferImages gbufferImages{
            {gbuffer.color.view, kColorFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {gbuffer.depthOut.view, kDepthOutFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {gbuffer.velocity.view, kVelocityFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {gbuffer.normal.view, kNormalFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL},
            {gbuffer.objectId.view, kObjectIdFormat, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL}};
        const hmb::EngineImage outputImage{output.view, kColorFormat, VK_IMAGE_LAYOUT_GENERAL};
        if (hybridBlur) hybridBlur->record(commands, gbufferImages, outputImage);
        else postProcess->record(commands, gbufferImages, outputImage);
        // ... and the blurred and the sharp colour copied for the host, which reads them after the fence.
        VkImageMemoryBarrier toCopy[2] = {toGeneral, toGeneral};
        toCopy[0].srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
        toCopy[0].oldLayout = VK_IMAGE_LAYOUT_GENERAL;
        toCopy[1].srcAccessMask = 0;  // read after read: the library's reads, then the copy's
        toCopy[1].oldLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
        toCopy[1].image = gbuffer.color.image;
        for (VkImageMemoryBarrier& b : toCopy) {
          b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
          b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
        }
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                             nullptr, 0, nullptr, 2, toCopy);
        const VkBufferImageCopy region{0, 0, 0, {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1}, {0, 0, 0}, {width, height, 1}};
        vkCmdCopyImageToBuffer(commands, output.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, blurred.buffer, 1, &region);
        vkCmdCopyImageToBuffer(commands, gbuffer.color.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, sharp.buffer, 1,
                               &region);
        VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        toHost.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
        toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                             VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0, nullptr);
        check(vkEndCommandBuffer(commands), "vkEndCommandBuffer");
        VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &commands;
        check(vkQueueSubmit(engine.queue, 1, &submit, fence), "vkQueueSubmit");
        check(vkWaitForFences(engine.device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        check(vkResetFences(engine.device, 1, &fence), "vkResetFences");

        char name[32];
        std::snprintf(name, sizeof(name), "frame-%02d", f);
        writePng(outDir / (std::string(name) + ".png"), static_cast<const float*>(blurred.mapped), width, height);
        writePng(outDir / (std::string(name) + "-sharp.png"), static_cast<const float*>(sharp.mapped), width, height);
        const hmb::EngineFrameTimes timings = hybridBlur ? hybridBlur->timings() : postProcess->timings();
        if (!timings.available()) {
          std::printf("%s: blurred (no device times: %s)\n", name, timings.unavailable.c_str());
          continue;
        }
        std::printf("%s: blurred in %.2f ms (", name, timings.frameMilliseconds);
        for (size_t p = 0; p < timings.passes.size(); ++p) {
          const hmb::EnginePassTime& pass = timings.passes[p];
          std::printf("%s%s", p ? ", " : "", pass.name.c_str());
          if (pass.runs > 1) std::printf(" x%u", pass.runs);
          std::printf(" %.2f", pass.milliseconds);
        }
        std::printf(")\n");
      }
      vkDestroyFence(engine.device, fence, nullptr);
      vkFreeCommandBuffers(engine.device, engine.pool, 1, &commands);
    }
    gbuffer.destroyWith(engine);
    destroy(engine, output);
    for (Buffer* b : {&blurred, &sharp, &vertices, &indices, &objects}) destroy(engine, *b);
    std::printf("wrote %d frames to %s\n", frames, outDir.string().c_str());
    if (validation && engine.messages > 0) {
      std::fprintf(stderr, "engine_backend: %u validation messages\n", engine.messages);
      return 3;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "engine_backend: %s\n", e.what());
    return 1;
  }
}
