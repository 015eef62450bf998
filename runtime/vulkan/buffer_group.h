// Buffers a kernel binds together (the trace scene, the scene's shading buffers, an image
// layer), from the group's first binding number on. A plain kernel build binds them one by one,
// in the group's order; a build that binds by address (vk::ComputeKernel::bindsByAddress) binds
// one table of their device addresses in that same order (the group's gpu::*Table in kernels/:
// one 64-bit address per buffer) at the first number. The
// table is written the first time a kernel binds the group by address, so devices whose
// kernels all bind plainly never pay for it, and made again when a member was made anew
// (its address changed).
#pragma once

#include <span>
#include <vector>

#include "hmblur/buffer.h"
#include "runtime/vulkan/binding.h"

namespace hmb::vk {

class BufferGroup {
 public:
  // Adds `members` (the group, in its order) at firstBinding on, or the table of their
  // addresses at firstBinding. Throws hmb::Error when the device has no buffer device addresses.
  void bind(Bindings& bindings, uint32_t firstBinding, bool byAddress, std::span<const Buffer* const> members) const;
 private:
  mutable Buffer table_;
  mutable std::vector<VkDeviceAddress> addresses_;  // what table_ holds
};

}  // namespace hmb::vk
