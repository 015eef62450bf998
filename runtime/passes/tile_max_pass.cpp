#include "runtime/passes/tile_max_pass.h"

#include <string>

#include <glm/glm.hpp>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "hmblur/post_process_settings.h"
#include "kernels/manifest.h"
#include "kernels/mblur/mblur_layout.h"
#include "kernels/shared/layer_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

TileMaxPass::TileMaxPass(const vk::Context& context)
    : kernel_(context, kernels::kernel("mblur/tile_max")) {}

void TileMaxPass::record(vk::FrameRecorder& frame, const vk::Buffer& velocities, const vk::Buffer& tiles,
                         uint32_t width, uint32_t height, uint32_t tileSize, float velocityScale,
                         std::string_view passName) const {
  if (velocities.size() < HMB_LAYER_VELOCITY_ENTRIES(uint64_t(width) * height) * sizeof(glm::vec2))
    throw Error(std::string(passName) + ": the velocities are fewer than " + std::to_string(width) + "x" +
                std::to_string(height) + " pixels'");
  const TileGrid grid = tileGridFor(width, height, tileSize);
  const gpu::TileMaxParams params{width, height, tileSize, grid.x, grid.y, velocityScale, 0, 0};
  // One group per tile.
  frame.dispatch(passName, kernel_,
                 {{HMB_TILE_MAX_BINDING_VELOCITIES, &velocities}, {HMB_TILE_MAX_BINDING_TILES, &tiles}}, params,
                 {grid.x, grid.y, 1});
}

}  // namespace hmb::passes
