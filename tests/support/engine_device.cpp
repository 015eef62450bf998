#include "tests/support/engine_device.h"

#include <algorithm>
#include <cstring>

#include <gtest/gtest.h>

#include "tests/support/image_2d.h"

namespace hmb::test {

Engine::OwnBuffer Engine::makeBuffer(VkDeviceSize size, std::span<const std::byte> bytes) {
  OwnBuffer b;
  b.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  EXPECT_EQ(vkCreateBuffer(device, &info, nullptr, &b.buffer), VK_SUCCESS);
  VkMemoryRequirements needs{};
  vkGetBufferMemoryRequirements(device, b.buffer, &needs);
  VkPhysicalDeviceMemoryProperties memory{};
  vkGetPhysicalDeviceMemoryProperties(physicalDevice, &memory);
  const VkMemoryPropertyFlags wanted = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  uint32_t type = 0;
  while (type < memory.memoryTypeCount &&
         !((needs.memoryTypeBits >> type & 1u) && (memory.memoryTypes[type].propertyFlags & wanted) == wanted))
    ++type;
  VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocation.allocationSize = needs.size;
  allocation.memoryTypeIndex = type;
  EXPECT_EQ(vkAllocateMemory(device, &allocation, nullptr, &b.memory), VK_SUCCESS);
  EXPECT_EQ(vkBindBufferMemory(device, b.buffer, b.memory, 0), VK_SUCCESS);
  void* mapped = nullptr;
  EXPECT_EQ(vkMapMemory(device, b.memory, 0, VK_WHOLE_SIZE, 0, &mapped), VK_SUCCESS);
  std::memset(mapped, 0, size);
  if (!bytes.empty()) std::memcpy(mapped, bytes.data(), std::min<size_t>(bytes.size(), size));
  vkUnmapMemory(device, b.memory);
  return b;
}

std::vector<std::byte> Engine::read(const OwnBuffer& buffer) const {
  std::vector<std::byte> bytes(buffer.size);
  void* mapped = nullptr;
  EXPECT_EQ(vkMapMemory(device, buffer.memory, 0, VK_WHOLE_SIZE, 0, &mapped), VK_SUCCESS);
  std::memcpy(bytes.data(), mapped, bytes.size());
  vkUnmapMemory(device, buffer.memory);
  return bytes;
}

void Engine::destroy(OwnBuffer& buffer) {
  vkDestroyBuffer(device, buffer.buffer, nullptr);
  vkFreeMemory(device, buffer.memory, nullptr);
  buffer = {};
}

namespace {

bool isDepth(VkFormat format) {
  return format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM || format == VK_FORMAT_X8_D24_UNORM_PACK32;
}

// A layout change of the whole image, after everything before it and before everything after.
void transition(VkCommandBuffer commands, VkImage image, VkFormat format, VkImageLayout from, VkImageLayout to) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VkImageAspectFlags(isDepth(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT),
                              0, 1, 0, 1};
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr,
                       0, nullptr, 1, &barrier);
}

}  // namespace

Engine::OwnImage Engine::makeImage(uint32_t width, uint32_t height, VkFormat format, uint32_t texelBytes,
                                   VkImageUsageFlags usage, std::span<const std::byte> texels, VkImageLayout layout) {
  OwnImage o;
  o.format = format;
  o.width = width;
  o.height = height;
  o.texelBytes = texelBytes;
  const VkImageCreateInfo info =
      image2DInfo(width, height, format, usage | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  EXPECT_EQ(vkCreateImage(device, &info, nullptr, &o.image), VK_SUCCESS);
  VkMemoryRequirements needs{};
  vkGetImageMemoryRequirements(device, o.image, &needs);
  uint32_t type = 0;
  while (type < 32 && !(needs.memoryTypeBits >> type & 1u)) ++type;
  VkMemoryAllocateInfo allocation{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  allocation.allocationSize = needs.size;
  allocation.memoryTypeIndex = type;
  EXPECT_EQ(vkAllocateMemory(device, &allocation, nullptr, &o.memory), VK_SUCCESS);
  EXPECT_EQ(vkBindImageMemory(device, o.image, o.memory, 0), VK_SUCCESS);
  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = o.image;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = format;
  viewInfo.subresourceRange = {VkImageAspectFlags(isDepth(format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT),
                               0, 1, 0, 1};
  EXPECT_EQ(vkCreateImageView(device, &viewInfo, nullptr, &o.view), VK_SUCCESS);
  OwnBuffer staging = makeBuffer(VkDeviceSize(width) * height * texelBytes, texels);
  const VkCommandBuffer commands = beginCommands();
  transition(commands, o.image, format, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  VkBufferImageCopy region{};
  region.imageSubresource = {viewInfo.subresourceRange.aspectMask, 0, 0, 1};
  region.imageExtent = {width, height, 1};
  vkCmdCopyBufferToImage(commands, staging.buffer, o.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
  transition(commands, o.image, format, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, layout);
  submitAndWait(commands);
  destroy(staging);
  return o;
}

std::vector<std::byte> Engine::read(const OwnImage& image, VkImageLayout layout) {
  OwnBuffer staging = makeBuffer(VkDeviceSize(image.width) * image.height * image.texelBytes);
  const VkCommandBuffer commands = beginCommands();
  transition(commands, image.image, image.format, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  VkBufferImageCopy region{};
  region.imageSubresource = {VkImageAspectFlags(isDepth(image.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT),
                             0, 0, 1};
  region.imageExtent = {image.width, image.height, 1};
  vkCmdCopyImageToBuffer(commands, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
  transition(commands, image.image, image.format, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
  submitAndWait(commands);
  std::vector<std::byte> bytes = read(staging);
  destroy(staging);
  return bytes;
}

void Engine::destroy(OwnImage& image) {
  vkDestroyImageView(device, image.view, nullptr);
  vkDestroyImage(device, image.image, nullptr);
  vkFreeMemory(device, image.memory, nullptr);
  image = {};
}

VkCommandBuffer Engine::beginCommands() {
  if (!commandPool) {
    VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    info.queueFamilyIndex = queueFamily;
    EXPECT_EQ(vkCreateCommandPool(device, &info, nullptr, &commandPool), VK_SUCCESS);
  }
  VkCommandBufferAllocateInfo allocation{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocation.commandPool = commandPool;
  allocation.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocation.commandBufferCount = 1;
  VkCommandBuffer commands = VK_NULL_HANDLE;
  EXPECT_EQ(vkAllocateCommandBuffers(device, &allocation, &commands), VK_SUCCESS);
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  EXPECT_EQ(vkBeginCommandBuffer(commands, &begin), VK_SUCCESS);
  return commands;
}

void Engine::submitAndWait(VkCommandBuffer commands) {
  // The host reads what the commands wrote.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(commands, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &barrier, 0,
                       nullptr, 0, nullptr);
  EXPECT_EQ(vkEndCommandBuffer(commands), VK_SUCCESS);
  VkQueue queue = VK_NULL_HANDLE;
  vkGetDeviceQueue(device, queueFamily, 0, &queue);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &commands;
  EXPECT_EQ(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE), VK_SUCCESS);
  EXPECT_EQ(vkQueueWaitIdle(queue), VK_SUCCESS);
  vkFreeCommandBuffers(device, commandPool, 1, &commands);
}

}  // namespace hmb::test
