#include "tests/oracle/oracle_vulkan.h"

#include <string>
#include <vector>

#include "runtime/error.h"
#include "runtime/vulkan/check.h"
#include "runtime/vulkan/context.h"

namespace hmb::oracle {

VkShaderModule createShader(VkDevice device, const uint32_t* words, size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = words;
  VkShaderModule module = VK_NULL_HANDLE;
  HMB_VK_CHECK(vkCreateShaderModule(device, &info, nullptr, &module));
  return module;
}

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
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
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
