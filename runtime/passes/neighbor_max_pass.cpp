#include "runtime/passes/neighbor_max_pass.h"

#include "kernels/manifest.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

NeighborMaxPass::NeighborMaxPass(const vk::Context& context)
    : kernel_(context, kernels::kernel("mblur/neighbor_max")) {}

void NeighborMaxPass::record(vk::FrameRecorder& frame, const vk::Buffer& tileMax, const vk::Buffer& neighborMax,
                             TileGrid grid, uint32_t neighborhood, std::string_view passName) const {
  const gpu::NeighborMaxParams params{grid.x, grid.y, neighborhood, 0};
  frame.dispatch(passName, kernel_, {{HMB_NEIGHBOR_MAX_BINDING_TILE_MAX, &tileMax}, {HMB_NEIGHBOR_MAX_BINDING_NEIGHBOR_MAX, &neighborMax}},
                 params,
                 {vk::groupsFor(grid.x, HMB_NEIGHBOR_MAX_GROUP_X), vk::groupsFor(grid.y, HMB_NEIGHBOR_MAX_GROUP_Y), 1});
}

}  // namespace hmb::passes
