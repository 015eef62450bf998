// Host side of kernels/mblur/tile_max.comp: per tile, the largest gather velocity.
#pragma once

#include <cstdint>
#include <string_view>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class TileMaxPass {
 public:
  static constexpr const char* kName = "tile-max";
  explicit TileMaxPass(const vk::Context& context);
  // velocities: a G-buffer's velocities (kernels/shared/layer_layout.h), pixels per frame, for
  // width * height pixels. tiles: tileGridFor(...).count() vec4
  // (layout: kernels/mblur/mblur_layout.h). velocityScale: PostProcessSettings::velocityScale().
  void record(vk::FrameRecorder& frame, const vk::Buffer& velocities, const vk::Buffer& tiles, uint32_t width,
              uint32_t height, uint32_t tileSize, float velocityScale, std::string_view passName = kName) const;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
