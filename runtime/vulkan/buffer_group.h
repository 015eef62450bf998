// Buffers a kernel binds together (the trace scene, the scene's shading buffers, an image
// layer). A plain kernel build binds them one by one, in the group's order; a build that binds
// by address (vk::ComputeKernel::bindsByAddress) binds one table of their device addresses in
// that same order (the group's gpu::*Table in kernels/: one 64-bit address per buffer). The
// table is written the first time a kernel binds the group by address, so devices whose
// kernels all bind plainly never pay for it.
#pragma once

#include <span>
#include <vector>

#include "runtime/vulkan/buffer.h"

namespace hmb::vk {

class BufferGroup {
 public:
  // Appends `members` (the group, in its order), or the table of their addresses, to a
  // kernel's bindings. Throws hmb::Error when the device has no buffer device addresses.
  void append(std::vector<const Buffer*>& bindings, bool byAddress, std::span<const Buffer* const> members) const;
  // A member was made anew: the next binding by address writes the table again.
  void forgetTable() { table_ = {}; }

 private:
  mutable Buffer table_;
};

}  // namespace hmb::vk
