// What the graphics-pipeline oracles (graphics_raster.h, graphics_gbuffer.h) build alike: shader
// modules, attachments, the depth format, the graphics-queue check and the draw's timestamps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

namespace hmb::vk {
class Context;
}

namespace hmb::oracle {

VkShaderModule createShader(VkDevice device, const uint32_t* words, size_t bytes);

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
