#include "tests/oracle/graphics_gbuffer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gbuffer_frag.spv.h"
#include "gbuffer_vert.spv.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/shared/layer_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/vulkan/check.h"
#include "tests/oracle/shaders/gbuffer_oracle_layout.h"

namespace hmb::oracle {
namespace {

constexpr VkFormat kRecordFormat = VK_FORMAT_R32G32B32A32_UINT;  // one packed record per pixel

}  // namespace

GraphicsGBuffer::GraphicsGBuffer(const vk::Context& context, const GpuScene& scene,
                                 std::span<const glm::vec4> clipCurrent, std::span<const glm::vec4> clipPrevious,
                                 std::span<const gpu::GpuVertexShading> shading, uint32_t width, uint32_t height)
    : context_(context), width_(width), height_(height), timer_(context) {
  if (width == 0 || height == 0) throw Error("G-buffer oracle: image size must be at least 1x1");
  if (clipCurrent.size() < scene.instanceVertexCount() || clipPrevious.size() < scene.instanceVertexCount() ||
      shading.size() < scene.instanceVertexCount())
    throw Error("G-buffer oracle: fewer transformed vertices than the scene has");
  requireGraphicsQueue(context, "G-buffer oracle");
  depthFormat_ = pickDepthFormat(context, "G-buffer oracle");

  // What the resolve writes where no triangle is: the background colour at the far depth.
  const gpu::GpuCamera camera = scene.cameraBuffer().download<gpu::GpuCamera>().at(0);
  const float far = scene.camera().zfar;
  backgroundSample_ = gpu::packLayerSample(glm::vec3(camera.background), far, glm::vec2(0.0f));
  backgroundSurface_ = gpu::packLayerSurface(glm::vec3(0.0f), 0u, far, glm::vec2(0.0f));

  // Consecutive triangles of the same sidedness share one draw, in id order (equal depths: the
  // first drawn wins, as the smallest id does in the compute rasterizer).
  std::vector<gpu::GpuTriangle> triangles = scene.triangles().download<gpu::GpuTriangle>();
  triangles.resize(scene.triangleCount());
  const std::vector<gpu::GpuInstance> instances = scene.instances().download<gpu::GpuInstance>();
  for (uint32_t t = 0; t < triangles.size(); ++t)
    addTriangle(draws_, t, (instances.at(triangles[t].instance).flags & HMB_INSTANCE_DOUBLE_SIDED) != 0);
  auto atLeastOne = [](auto values) {
    if (values.empty()) values.resize(1);
    return values;
  };
  triangles_ = vk::uploadedBuffer(context, atLeastOne(triangles), "G-buffer oracle triangles");
  clipCurrent_ = vk::uploadedBuffer(context, atLeastOne(std::vector(clipCurrent.begin(), clipCurrent.end())),
                                    "G-buffer oracle clip positions");
  clipPrevious_ = vk::uploadedBuffer(context, atLeastOne(std::vector(clipPrevious.begin(), clipPrevious.end())),
                                     "G-buffer oracle previous clip positions");
  shading_ = vk::uploadedBuffer(context, atLeastOne(std::vector(shading.begin(), shading.end())),
                                "G-buffer oracle vertex shading");
  try {
    createRenderPass();
    createFramebuffer();
    createDescriptors(scene);
    createPipelines(scene.texturePath());
    const VkDeviceSize bytes = VkDeviceSize(width) * height * sizeof(glm::uvec4);
    samplesReadback_ = vk::Buffer(context, bytes, vk::MemoryUse::Readback, "G-buffer oracle samples (readback)");
    surfacesReadback_ = vk::Buffer(context, bytes, vk::MemoryUse::Readback, "G-buffer oracle surfaces (readback)");
  } catch (...) {
    release();
    throw;
  }
}

GraphicsGBuffer::~GraphicsGBuffer() { release(); }

void GraphicsGBuffer::release() {
  const VkDevice device = context_.device();
  destroyOracleDraw(device, pipelines_, pipelineLayout_, framebuffer_, renderPass_);
  if (pool_) vkDestroyDescriptorPool(device, pool_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
  destroyAttachment(context_, samples_);
  destroyAttachment(context_, surfaces_);
  destroyAttachment(context_, depth_);
  pool_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
  setLayout_ = VK_NULL_HANDLE;
}

void GraphicsGBuffer::createRenderPass() {
  const VkFormat colorFormats[] = {kRecordFormat, kRecordFormat};
  renderPass_ = createReadbackRenderPass(context_, colorFormats, depthFormat_);
}

void GraphicsGBuffer::createFramebuffer() {
  samples_ = createAttachment(context_, width_, height_, kRecordFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                              VK_IMAGE_ASPECT_COLOR_BIT);
  surfaces_ = createAttachment(context_, width_, height_, kRecordFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                               VK_IMAGE_ASPECT_COLOR_BIT);
  depth_ = createAttachment(context_, width_, height_, depthFormat_, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                            VK_IMAGE_ASPECT_DEPTH_BIT);
  const VkImageView views[3] = {samples_.view, surfaces_.view, depth_.view};
  framebuffer_ = createReadbackFramebuffer(context_, renderPass_, views, width_, height_);
}

void GraphicsGBuffer::createDescriptors(const GpuScene& scene) {
  const VkDevice device = context_.device();
  // The shading function reads the scene's vertices, instances, materials and texels as
  // uniform texel buffers (kernels/shared/scene_bindings.glsl); every other binding is a
  // storage buffer.
  auto typeOf = [](uint32_t binding) {
    const bool texels = binding >= HMB_GBUFFER_ORACLE_BINDING_SCENE &&
                        binding < HMB_GBUFFER_ORACLE_BINDING_SCENE + HMB_SCENE_TEXEL_BUFFERS;
    return texels ? VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
  };
  VkDescriptorSetLayoutBinding bindings[HMB_GBUFFER_ORACLE_BINDING_COUNT]{};
  for (uint32_t i = 0; i < HMB_GBUFFER_ORACLE_BINDING_COUNT; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = typeOf(i);
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  }
  VkDescriptorSetLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  layoutInfo.bindingCount = HMB_GBUFFER_ORACLE_BINDING_COUNT;
  layoutInfo.pBindings = bindings;
  HMB_VK_CHECK(vkCreateDescriptorSetLayout(device, &layoutInfo, nullptr, &setLayout_));

  const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, HMB_GBUFFER_ORACLE_BINDING_COUNT},
                                        {VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER, HMB_SCENE_TEXEL_BUFFERS}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.maxSets = 1;
  poolInfo.poolSizeCount = 2;
  poolInfo.pPoolSizes = sizes;
  HMB_VK_CHECK(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool_));
  VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  alloc.descriptorPool = pool_;
  alloc.descriptorSetCount = 1;
  alloc.pSetLayouts = &setLayout_;
  HMB_VK_CHECK(vkAllocateDescriptorSets(device, &alloc, &set_));

  // The order of HMB_GBUFFER_ORACLE_BINDING_*, then the scene's as scene_bindings.glsl has it.
  const vk::Buffer* buffers[HMB_GBUFFER_ORACLE_BINDING_COUNT] = {
      &triangles_,          &clipCurrent_,       &clipPrevious_,    &shading_,          &scene.vertices(),
      &scene.instances(),   &scene.materials(),  &scene.texels(),   &scene.cameraBuffer()};
  VkDescriptorBufferInfo infos[HMB_GBUFFER_ORACLE_BINDING_COUNT]{};
  VkWriteDescriptorSet writes[HMB_GBUFFER_ORACLE_BINDING_COUNT]{};
  VkBufferView views[HMB_GBUFFER_ORACLE_BINDING_COUNT]{};
  for (uint32_t i = 0; i < HMB_GBUFFER_ORACLE_BINDING_COUNT; ++i)
    if (typeOf(i) == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER) views[i] = buffers[i]->texelView();

  for (uint32_t i = 0; i < HMB_GBUFFER_ORACLE_BINDING_COUNT; ++i) {
    infos[i] = {buffers[i]->handle(), 0, VK_WHOLE_SIZE};
    writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    writes[i].dstSet = set_;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = typeOf(i);
    if (typeOf(i) == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER)
      writes[i].pTexelBufferView = &views[i];
    else
      writes[i].pBufferInfo = &infos[i];
  }
  vkUpdateDescriptorSets(device, HMB_GBUFFER_ORACLE_BINDING_COUNT, writes, 0, nullptr);

  const VkPushConstantRange push{VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(gpu::GBufferOracleParams)};
  VkPipelineLayoutCreateInfo pipelineLayoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pipelineLayoutInfo.setLayoutCount = 1;
  pipelineLayoutInfo.pSetLayouts = &setLayout_;
  pipelineLayoutInfo.pushConstantRangeCount = 1;
  pipelineLayoutInfo.pPushConstantRanges = &push;
  HMB_VK_CHECK(vkCreatePipelineLayout(device, &pipelineLayoutInfo, nullptr, &pipelineLayout_));
}

void GraphicsGBuffer::createPipelines(bool texturePath) {
  // The texture path as the resolve kernel is built for this scene (shading.glsl).
  const VkSpecializationMapEntry entry{HMB_SPEC_TEXTURE_PATH, 0, sizeof(VkBool32)};
  const VkBool32 texture = texturePath ? VK_TRUE : VK_FALSE;
  const VkSpecializationInfo specialization{1, &entry, sizeof(texture), &texture};
  const VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  createOraclePipelines(context_.device(), {kGBuffer_vert, kGBuffer_frag, &specialization}, vertexInput, 2,
                        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                            VK_COLOR_COMPONENT_A_BIT,
                        pipelineLayout_, renderPass_, width_, height_, pipelines_);
}

GraphicsGBuffer::Image GraphicsGBuffer::render() {
  context_.submitAndWait([&](VkCommandBuffer cmd) {
    timer_.begin(cmd);
    VkClearValue clears[3]{};
    for (int c = 0; c < 4; ++c) {
      clears[0].color.uint32[c] = backgroundSample_[c];
      clears[1].color.uint32[c] = backgroundSurface_[c];
    }
    clears[2].depthStencil = {0.0f, 0};  // the far plane
    beginReadbackPass(cmd, renderPass_, framebuffer_, width_, height_, clears);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelineLayout_, 0, 1, &set_, 0, nullptr);
    const gpu::GBufferOracleParams params{width_, height_, 0, 0};
    vkCmdPushConstants(cmd, pipelineLayout_, VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(params), &params);
    recordDrawSpans(cmd, pipelines_, draws_);
    vkCmdEndRenderPass(cmd);
    timer_.end(cmd);

    VkBufferImageCopy region{};
    region.imageExtent = {width_, height_, 1};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    vkCmdCopyImageToBuffer(cmd, samples_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, samplesReadback_.handle(), 1,
                           &region);
    vkCmdCopyImageToBuffer(cmd, surfaces_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, surfacesReadback_.handle(), 1,
                           &region);
    barrierToHost(cmd);
  });
  lastDrawMs_ = timer_.milliseconds();
  return {samplesReadback_.download<glm::uvec4>(), surfacesReadback_.download<glm::uvec4>()};
}

GBufferAgreement compareGBuffers(std::span<const glm::uvec4> samples, std::span<const glm::uvec4> surfaces,
                                 const GraphicsGBuffer::Image& oracle) {
  const size_t pixels = oracle.samples.size();
  if (samples.size() < pixels || surfaces.size() < pixels) throw Error("G-buffer comparison: the layer is too small");
  GBufferAgreement a;
  size_t sameObject = 0, onObject = 0, withinTolerance = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t id = gpu::surfaceObjectId(surfaces[i]);
    if (id != gpu::surfaceObjectId(oracle.surfaces[i])) continue;
    ++sameObject;
    if (id == 0) continue;
    ++onObject;
    const double da = gpu::sampleDepth(samples[i]), db = gpu::sampleDepth(oracle.samples[i]);
    const double depth = std::abs(da - db) / std::max({std::abs(da), std::abs(db), 1e-30});
    const glm::dvec3 ca = glm::dvec3(gpu::sampleColor(samples[i])), cb = glm::dvec3(gpu::sampleColor(oracle.samples[i]));
    const double color = std::max({std::abs(ca.x - cb.x), std::abs(ca.y - cb.y), std::abs(ca.z - cb.z)});
    const double velocity = glm::length(glm::dvec2(gpu::surfaceVelocity(surfaces[i])) -
                                        glm::dvec2(gpu::surfaceVelocity(oracle.surfaces[i])));
    const double cosine = glm::dot(glm::dvec3(gpu::surfaceNormal(surfaces[i])), glm::dvec3(gpu::surfaceNormal(oracle.surfaces[i])));
    const double normal = std::acos(std::clamp(cosine, -1.0, 1.0));
    a.depthRelative = std::max(a.depthRelative, depth);
    a.color = std::max(a.color, color);
    a.velocityPixels = std::max(a.velocityPixels, velocity);
    a.normalRadians = std::max(a.normalRadians, normal);
    withinTolerance += depth <= kDepthTolerance && color <= kColorTolerance && velocity <= kVelocityTolerance &&
                       normal <= kNormalTolerance;
  }
  if (pixels > 0) a.objectIds = double(sameObject) / double(pixels);
  if (onObject > 0) a.attributes = double(withinTolerance) / double(onObject);
  return a;
}

}  // namespace hmb::oracle
