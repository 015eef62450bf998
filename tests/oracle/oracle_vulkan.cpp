#include "tests/oracle/oracle_vulkan.h"

#include <string>
#include <vector>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "runtime/vulkan/check.h"
#include "tests/support/image_2d.h"

namespace hmb::oracle {
namespace {

VkShaderModule createShader(VkDevice device, const uint32_t* words, size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = words;
  VkShaderModule module = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
  return module;
}

}  // namespace

void requireGraphicsQueue(const vk::Context& context, const char* who) {
  uint32_t familyCount = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &familyCount, nullptr);
  std::vector<VkQueueFamilyProperties> families(familyCount);
  vkGetPhysicalDeviceQueueFamilyProperties(context.physicalDevice(), &familyCount, families.data());
  if (!(families.at(context.queueFamily()).queueFlags & VK_QUEUE_GRAPHICS_BIT))
    throw Error(std::string(who) + ": the context's queue family has no graphics support");
}

VkFormat pickDepthFormat(const vk::Context& context, const char* who) {
  for (VkFormat format : {VK_FORMAT_D32_SFLOAT, VK_FORMAT_D32_SFLOAT_S8_UINT, VK_FORMAT_X8_D24_UNORM_PACK32}) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(context.physicalDevice(), format, &props);
    const VkFormatFeatureFlags needed =
        VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
    if ((props.optimalTilingFeatures & needed) == needed) return format;
  }
  throw Error(std::string(who) + ": no usable depth format");
}

Attachment createAttachment(const vk::Context& context, uint32_t width, uint32_t height, VkFormat format,
                            VkImageUsageFlags usage, VkImageAspectFlags aspect) {
  const VkDevice device = context.device();
  Attachment a;
  const VkImageCreateInfo info = test::image2DInfo(width, height, format, usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  try {
    HMB_VK_CHECK(vkCreateImage(device, &info, nullptr, &a.image));
    VkMemoryRequirements req{};
    vkGetImageMemoryRequirements(device, a.image, &req);
    uint32_t type = context.findMemoryType(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    if (type == UINT32_MAX) type = context.findMemoryType(req.memoryTypeBits, 0);
    if (type == UINT32_MAX) throw Error("graphics oracle: no memory type fits an attachment");
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = context.allocationType(type);
    HMB_VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &a.memory));
    HMB_VK_CHECK(vkBindImageMemory(device, a.image, a.memory, 0));

    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = a.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format;
    view.subresourceRange = {aspect, 0, 1, 0, 1};
    HMB_VK_CHECK(vkCreateImageView(device, &view, nullptr, &a.view));
  } catch (...) {
    destroyAttachment(context, a);
    throw;
  }
  return a;
}

void destroyAttachment(const vk::Context& context, Attachment& a) {
  const VkDevice device = context.device();
  if (a.view) vkDestroyImageView(device, a.view, nullptr);
  if (a.image) vkDestroyImage(device, a.image, nullptr);
  if (a.memory) vkFreeMemory(device, a.memory, nullptr);
  a = Attachment{};
}

VkRenderPass createReadbackRenderPass(const vk::Context& context, std::span<const VkFormat> colorFormats,
                                      VkFormat depthFormat) {
  std::vector<VkAttachmentDescription> attachments(colorFormats.size() + 1);
  std::vector<VkAttachmentReference> colorRefs;
  for (size_t i = 0; i < attachments.size(); ++i) {
    VkAttachmentDescription& a = attachments[i];
    a.format = i < colorFormats.size() ? colorFormats[i] : depthFormat;
    a.samples = VK_SAMPLE_COUNT_1_BIT;
    a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;  // every frame clears: old contents are not needed
    a.finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    if (i < colorFormats.size()) colorRefs.push_back({uint32_t(i), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
  }
  const VkAttachmentReference depthRef{uint32_t(colorFormats.size()), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
  VkSubpassDescription subpass{};
  subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  subpass.colorAttachmentCount = uint32_t(colorRefs.size());
  subpass.pColorAttachments = colorRefs.data();
  subpass.pDepthStencilAttachment = &depthRef;

  constexpr VkPipelineStageFlags attachmentStages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                    VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                    VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  constexpr VkAccessFlags attachmentWrites =
      VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  VkSubpassDependency dependencies[2]{};
  dependencies[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[0].dstSubpass = 0;
  dependencies[0].srcStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[0].dstStageMask = attachmentStages;
  dependencies[0].dstAccessMask = attachmentWrites | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
  dependencies[1].srcSubpass = 0;
  dependencies[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  dependencies[1].srcStageMask = attachmentStages;
  dependencies[1].dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
  dependencies[1].srcAccessMask = attachmentWrites;
  dependencies[1].dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;

  VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  info.attachmentCount = uint32_t(attachments.size());
  info.pAttachments = attachments.data();
  info.subpassCount = 1;
  info.pSubpasses = &subpass;
  info.dependencyCount = 2;
  info.pDependencies = dependencies;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkCreateRenderPass(context.device(), &info, nullptr, &renderPass));
  return renderPass;
}

VkFramebuffer createReadbackFramebuffer(const vk::Context& context, VkRenderPass renderPass,
                                        std::span<const VkImageView> views, uint32_t width, uint32_t height) {
  VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  info.renderPass = renderPass;
  info.attachmentCount = uint32_t(views.size());
  info.pAttachments = views.data();
  info.width = width;
  info.height = height;
  info.layers = 1;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkCreateFramebuffer(context.device(), &info, nullptr, &framebuffer));
  return framebuffer;
}

void beginReadbackPass(VkCommandBuffer cmd, VkRenderPass renderPass, VkFramebuffer framebuffer, uint32_t width,
                       uint32_t height, std::span<const VkClearValue> clears) {
  VkRenderPassBeginInfo begin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  begin.renderPass = renderPass;
  begin.framebuffer = framebuffer;
  begin.renderArea = {{0, 0}, {width, height}};
  begin.clearValueCount = uint32_t(clears.size());
  begin.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
}

namespace {

// Both pipelines from the shader stages.
void createPipelinesFromStages(VkDevice device, std::span<const VkPipelineShaderStageCreateInfo> stages,
                               const VkPipelineVertexInputStateCreateInfo& vertexInput, uint32_t colorAttachments,
                               VkColorComponentFlags writeMask, VkPipelineLayout layout, VkRenderPass renderPass,
                               uint32_t width, uint32_t height, VkPipeline pipelines[2]) {
  VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  const VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, {width, height}};
  VkPipelineViewportStateCreateInfo viewportState{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewportState.viewportCount = 1;
  viewportState.pViewports = &viewport;
  viewportState.scissorCount = 1;
  viewportState.pScissors = &scissor;
  VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.depthClampEnable = VK_FALSE;
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  depth.depthTestEnable = VK_TRUE;
  depth.depthWriteEnable = VK_TRUE;
  depth.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed depth: nearer is larger
  std::vector<VkPipelineColorBlendAttachmentState> blendAttachments(colorAttachments);
  for (VkPipelineColorBlendAttachmentState& b : blendAttachments) b.colorWriteMask = writeMask;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = colorAttachments;
  blend.pAttachments = blendAttachments.data();

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.stageCount = uint32_t(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewportState;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.layout = layout;
  info.renderPass = renderPass;
  const VkCullModeFlags cullModes[2] = {VK_CULL_MODE_BACK_BIT, VK_CULL_MODE_NONE};
  for (int i = 0; i < 2; ++i) {
    raster.cullMode = cullModes[i];
    HMB_VK_CHECK(vkCreateGraphicsPipelines(device, VK_NULL_HANDLE, 1, &info, nullptr, &pipelines[i]));
  }
}

}  // namespace

void createOraclePipelines(VkDevice device, const OracleShaders& shaders,
                           const VkPipelineVertexInputStateCreateInfo& vertexInput, uint32_t colorAttachments,
                           VkColorComponentFlags writeMask, VkPipelineLayout layout, VkRenderPass renderPass,
                           uint32_t width, uint32_t height, VkPipeline pipelines[2]) {
  VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
  try {
    vert = createShader(device, shaders.vertex.data(), shaders.vertex.size_bytes());
    frag = createShader(device, shaders.fragment.data(), shaders.fragment.size_bytes());
    VkPipelineShaderStageCreateInfo stages[2]{};
    stages[0].sType = stages[1].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
    stages[0].module = vert;
    stages[0].pName = "main";
    stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
    stages[1].module = frag;
    stages[1].pName = "main";
    stages[1].pSpecializationInfo = shaders.fragmentSpecialization;
    createPipelinesFromStages(device, stages, vertexInput, colorAttachments, writeMask, layout, renderPass, width,
                              height, pipelines);
  } catch (...) {
    if (vert) vkDestroyShaderModule(device, vert, nullptr);
    if (frag) vkDestroyShaderModule(device, frag, nullptr);
    throw;
  }
  vkDestroyShaderModule(device, vert, nullptr);
  vkDestroyShaderModule(device, frag, nullptr);
}

void destroyOracleDraw(VkDevice device, VkPipeline pipelines[2], VkPipelineLayout& layout, VkFramebuffer& framebuffer,
                       VkRenderPass& renderPass) {
  for (int i = 0; i < 2; ++i) {
    if (pipelines[i]) vkDestroyPipeline(device, pipelines[i], nullptr);
    pipelines[i] = VK_NULL_HANDLE;
  }
  if (layout) vkDestroyPipelineLayout(device, layout, nullptr);
  if (framebuffer) vkDestroyFramebuffer(device, framebuffer, nullptr);
  if (renderPass) vkDestroyRenderPass(device, renderPass, nullptr);
  layout = VK_NULL_HANDLE;
  framebuffer = VK_NULL_HANDLE;
  renderPass = VK_NULL_HANDLE;
}

void addTriangle(std::vector<DrawSpan>& spans, uint32_t t, bool doubleSided) {
  const uint32_t pipeline = doubleSided ? 1 : 0;
  if (spans.empty() || spans.back().pipeline != pipeline) spans.push_back({pipeline, 3 * t, 0});
  spans.back().vertexCount += 3;
}

void recordDrawSpans(VkCommandBuffer cmd, const VkPipeline pipelines[2], std::span<const DrawSpan> spans) {
  uint32_t bound = UINT32_MAX;
  for (const DrawSpan& span : spans) {
    if (span.pipeline != bound) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipelines[span.pipeline]);
    bound = span.pipeline;
    vkCmdDraw(cmd, span.vertexCount, 1, span.firstVertex, 0);
  }
}

void barrierToHost(VkCommandBuffer cmd) {
  VkMemoryBarrier toHost{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  toHost.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  toHost.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &toHost, 0, nullptr, 0,
                       nullptr);
}

DrawTimer::DrawTimer(const vk::Context& context) : context_(context) {
  if (!context.info().timestamps) return;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2;
  HMB_VK_CHECK(vkCreateQueryPool(context.device(), &info, nullptr, &pool_));
}

DrawTimer::~DrawTimer() {
  if (pool_) vkDestroyQueryPool(context_.device(), pool_, nullptr);
}

void DrawTimer::begin(VkCommandBuffer cmd) const {
  if (!pool_) return;
  vkCmdResetQueryPool(cmd, pool_, 0, 2);
  vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, pool_, 0);
}

void DrawTimer::end(VkCommandBuffer cmd) const {
  if (pool_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 1);
}

std::optional<double> DrawTimer::milliseconds() const {
  if (!pool_) return std::nullopt;
  uint64_t stamps[2] = {0, 0};
  HMB_VK_CHECK(vkGetQueryPoolResults(context_.device(), pool_, 0, 2, sizeof(stamps), stamps, sizeof(uint64_t),
                                     VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  const double ticks = double((stamps[1] - stamps[0]) & context_.info().timestampMask);
  return ticks * context_.info().timestampPeriodNs * 1e-6;
}

}  // namespace hmb::oracle
