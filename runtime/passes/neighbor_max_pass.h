// Host side of kernels/mblur/neighbor_max.comp: per tile, the largest tile-max around it.
#pragma once

#include <cstdint>
#include <string_view>

#include "hmblur/post_process_settings.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class NeighborMaxPass {
 public:
  static constexpr const char* kName = "neighbor-max";
  explicit NeighborMaxPass(const vk::Context& context);
  // tileMax, neighborMax: grid.count() vec4 each; neighborhood odd.
  void record(vk::FrameRecorder& frame, const vk::Buffer& tileMax, const vk::Buffer& neighborMax, TileGrid grid,
              uint32_t neighborhood, std::string_view passName = kName) const;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
