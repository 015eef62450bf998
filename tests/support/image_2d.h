// A 2D image as the tests make them: one mip level, one layer, one sample, optimal tiling,
// starting undefined.
#pragma once

#include <cstdint>

#include <vulkan/vulkan.h>

namespace hmb::test {

inline VkImageCreateInfo image2DInfo(uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return info;
}

}  // namespace hmb::test
