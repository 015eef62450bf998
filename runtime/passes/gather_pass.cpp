#include "runtime/passes/gather_pass.h"

#include <algorithm>
#include <span>

#include "runtime/error.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

gpu::GatherParams gatherParams(const PostProcessSettings& settings, uint32_t width, uint32_t height,
                               MaskWeights mask) {
  const uint32_t tileSize = settings.effectiveTileSize();
  const TileGrid grid = tileGridFor(width, height, tileSize);
  const uint32_t flags = settings.range == GatherRange::Adapted ? HMB_GATHER_FLAG_ADAPTED_RANGE : 0u;
  return gpu::GatherParams{width,
                           height,
                           tileSize,
                           grid.x,
                           grid.y,
                           settings.samples,
                           settings.seed,
                           flags,
                           gatherVelocityScale(settings.range, settings.exposure, settings.fps),
                           settings.softZExtent,
                           settings.effectiveForegroundBoost(),
                           mask.backgroundBoost,
                           mask.foregroundDivide,
                           float(std::max(width, height)),
                           0,
                           0};
}

GatherPass::GatherPass(const vk::Context& context) : kernel_(context, "mblur/gather", sizeof(gpu::GatherParams)) {}

std::unique_ptr<GatherFilter> makeMcGuireGather(const vk::Context& context) {
  return std::make_unique<GatherPass>(context);
}

void GatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                        const vk::Buffer& output, const PostProcessSettings& settings) const {
  gpu::GatherParams params = gatherParams(settings, inputs.width, inputs.height);
  if (settings.motionPath == MotionPath::Curved) {
    if (!inputs.shutterPaths) throw Error("post-process: the curved motion path needs the G-buffer's shutter paths");
    params.flags |= HMB_GATHER_FLAG_CURVED_PATH;
  }
  frame.dispatch(kName, kernel_, filterBindings(inputs, neighborMax, output), params,
                 {vk::groupsFor(inputs.width, HMB_GATHER_GROUP_X), vk::groupsFor(inputs.height, HMB_GATHER_GROUP_Y), 1});
}

}  // namespace hmb::passes
