#include "runtime/passes/jimenez_gather_pass.h"

#include "kernels/mblur/mblur_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

JimenezGatherPass::JimenezGatherPass(const vk::Context& context)
    : kernel_(context, "mblur/gather_jimenez", sizeof(gpu::JimenezParams)) {}

void JimenezGatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                               const vk::Buffer& neighborMax, const vk::Buffer& output,
                               const PostProcessSettings& settings, std::string_view passName) const {
  const TileGrid grid = tileGridFor(inputs.width, inputs.height, settings.jimenezTileSize);
  const gpu::JimenezParams params{inputs.width,
                                  inputs.height,
                                  settings.jimenezTileSize,
                                  grid.x,
                                  grid.y,
                                  settings.samples,
                                  settings.seed,
                                  0,
                                  gatherVelocityScale(GatherRange::Centered, settings.exposure, settings.fps),
                                  settings.softZExtent,
                                  settings.jimenezTileJitter,
                                  0};
  frame.dispatch(passName, kernel_, {inputs.color, inputs.normalDepth, inputs.velocity, &neighborMax, &output},
                 params,
                 {vk::groupsFor(inputs.width, HMB_GATHER_GROUP_X), vk::groupsFor(inputs.height, HMB_GATHER_GROUP_Y), 1});
}

}  // namespace hmb::passes
