// What the graphics-pipeline oracles (graphics_raster.h, graphics_gbuffer.h) build alike: their
// pipelines from their shaders, attachments, render pass and framebuffer, the depth format, the
// graphics-queue check, the draw's spans and timestamps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

namespace hmb::vk {
class Context;
}

namespace hmb::oracle {

// Throws hmb::Error naming `who` when the context's queue family cannot draw.
void requireGraphicsQueue(const vk::Context& context, const char* who);

// D32_SFLOAT (exact to float precision), else D32_SFLOAT_S8_UINT, else X8_D24 (which Vulkan
// guarantees); throws hmb::Error naming `who` when none is usable.
VkFormat pickDepthFormat(const vk::Context& context, const char* who);

struct Attachment {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};
// A width x height image the render pass draws into and the readback copies from.
Attachment createAttachment(const vk::Context& context, uint32_t width, uint32_t height, VkFormat format,
                            VkImageUsageFlags usage, VkImageAspectFlags aspect);
void destroyAttachment(const vk::Context& context, Attachment& attachment);

// One subpass drawing into colour attachments of `colorFormats` and a depth attachment (last),
// all cleared on load and left in TRANSFER_SRC_OPTIMAL: the dependencies order the previous
// frame's readback copies before the clears, and this frame's copies after the draws.
VkRenderPass createReadbackRenderPass(const vk::Context& context, std::span<const VkFormat> colorFormats,
                                      VkFormat depthFormat);

// The framebuffer of such a render pass over `views` (colour attachments, then depth).
VkFramebuffer createReadbackFramebuffer(const vk::Context& context, VkRenderPass renderPass,
                                        std::span<const VkImageView> views, uint32_t width, uint32_t height);
// Begins the render pass over the whole framebuffer with one clear value per attachment.
void beginReadbackPass(VkCommandBuffer cmd, VkRenderPass renderPass, VkFramebuffer framebuffer, uint32_t width,
                       uint32_t height, std::span<const VkClearValue> clears);

// An oracle's SPIR-V (vertex and fragment shader words), and the fragment shader's
// specialization if any.
struct OracleShaders {
  std::span<const uint32_t> vertex, fragment;
  const VkSpecializationInfo* fragmentSpecialization = nullptr;
};

// The oracles' two pipelines, [0] culling back faces and [1] none: triangle lists over the whole
// width x height viewport, depth clamp off (0 <= z/w <= 1, as the compute rasterizer keeps),
// counter-clockwise front faces (graphics_raster.h), reversed depth (GREATER test), one sample
// per pixel, `colorAttachments` attachments written with `writeMask`.
void createOraclePipelines(VkDevice device, const OracleShaders& shaders,
                           const VkPipelineVertexInputStateCreateInfo& vertexInput, uint32_t colorAttachments,
                           VkColorComponentFlags writeMask, VkPipelineLayout layout, VkRenderPass renderPass,
                           uint32_t width, uint32_t height, VkPipeline pipelines[2]);

// Destroys what an oracle draws with (each handle that is set) and clears the handles.
void destroyOracleDraw(VkDevice device, VkPipeline pipelines[2], VkPipelineLayout& layout, VkFramebuffer& framebuffer,
                       VkRenderPass& renderPass);

// Consecutive triangles of one sidedness, drawn with one of the two pipelines above in one call,
// so the draw order (which decides equal-depth ties) is the triangles' order.
struct DrawSpan {
  uint32_t pipeline, firstVertex, vertexCount;
};
// Appends triangle t (vertices 3t..3t+2) to the spans.
void addTriangle(std::vector<DrawSpan>& spans, uint32_t t, bool doubleSided);
void recordDrawSpans(VkCommandBuffer cmd, const VkPipeline pipelines[2], std::span<const DrawSpan> spans);
// Makes the readback copies recorded before it visible to the host.
void barrierToHost(VkCommandBuffer cmd);

// Two timestamps around a draw.
class DrawTimer {
 public:
  explicit DrawTimer(const vk::Context& context);  // no pool where the queue has no timestamps
  ~DrawTimer();
  DrawTimer(const DrawTimer&) = delete;
  DrawTimer& operator=(const DrawTimer&) = delete;
  void begin(VkCommandBuffer cmd) const;  // after the uploads: ALL_COMMANDS waits for them
  void end(VkCommandBuffer cmd) const;
  // After the submission: the draw's device milliseconds (empty without timestamps).
  std::optional<double> milliseconds() const;

 private:
  const vk::Context& context_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
};

}  // namespace hmb::oracle
