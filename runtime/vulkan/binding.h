// A buffer (or an engine's image) at one of a kernel's binding numbers, as the kernel's layout header names it
// (HMB_FILTER_BINDING_COLOR ...): passes bind buffers by those names, never by their position
// in a list, and the frame recorder checks the numbers against what the kernel declares.
#pragma once

#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

namespace hmb::vk {

class Buffer;

struct Binding {
  uint32_t index;
  const Buffer* buffer;
  // For a kernel's image bindings, in place of the buffer: an image view someone else owns (an
  // engine's) and the layout it is in when the pass runs.
  VkImageView image = VK_NULL_HANDLE;
  VkImageLayout imageLayout = VK_IMAGE_LAYOUT_UNDEFINED;
};

using Bindings = std::vector<Binding>;

}  // namespace hmb::vk
