#include "runtime/passes/jimenez_gather_pass.h"

#include "kernels/manifest.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

JimenezGatherPass::JimenezGatherPass(const vk::Context& context)
    : kernel_(context, kernels::kernel("mblur/gather_jimenez")) {}

std::unique_ptr<GatherFilter> makeJimenezGather(const vk::Context& context) {
  return std::make_unique<JimenezGatherPass>(context);
}

void JimenezGatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                               const vk::Buffer& neighborMax, const vk::Buffer& output,
                               const PostProcessSettings& settings) const {
  const uint32_t tileSize = settings.effectiveTileSize();
  const TileGrid grid = tileGridFor(inputs.width, inputs.height, tileSize);
  const gpu::JimenezParams params{inputs.width,
                                  inputs.height,
                                  tileSize,
                                  grid.x,
                                  grid.y,
                                  settings.samples,
                                  settings.seed,
                                  0,
                                  gatherVelocityScale(GatherRange::Centered, settings.exposure, settings.fps),
                                  settings.softZExtent,
                                  settings.jimenezTileJitter,
                                  0};
  frame.dispatch(kName, kernel_, filterBindings(inputs, neighborMax, output), params,
                 {vk::groupsFor(inputs.width, HMB_GATHER_GROUP_X), vk::groupsFor(inputs.height, HMB_GATHER_GROUP_Y), 1});
}

}  // namespace hmb::passes
