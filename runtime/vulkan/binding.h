// A buffer at one of a kernel's binding numbers, as the kernel's layout header names it
// (HMB_FILTER_BINDING_COLOR ...): passes bind buffers by those names, never by their position
// in a list, and the frame recorder checks the numbers against what the kernel declares.
#pragma once

#include <cstdint>
#include <vector>

namespace hmb::vk {

class Buffer;

struct Binding {
  uint32_t index;
  const Buffer* buffer;
};

using Bindings = std::vector<Binding>;

}  // namespace hmb::vk
