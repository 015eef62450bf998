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
                           settings.foregroundBoostPixelsPerSlice(),
                           0};
}

GatherPass::GatherPass(const vk::Context& context) : context_(context) {}

std::unique_ptr<GatherFilter> makeMcGuireGather(const vk::Context& context) {
  return std::make_unique<GatherPass>(context);
}

void GatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                        const vk::Buffer& output, const PostProcessSettings& settings) const {
  // The mask is read only by the hybrid's variant; the output stands in.
  recordWith(false, frame, inputs, neighborMax, output, settings, output);
}

void GatherPass::recordOutsideMask(vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                                   const vk::Buffer& neighborMax, const vk::Buffer& output,
                                   const PostProcessSettings& settings, const vk::Buffer& mask) const {
  recordWith(true, frame, inputs, neighborMax, output, settings, mask);
}

void GatherPass::recordWith(bool outsideMask, vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                            const vk::Buffer& neighborMax, const vk::Buffer& output,
                            const PostProcessSettings& settings, const vk::Buffer& mask) const {
  const bool curved = settings.motionPath == MotionPath::Curved;
  if (curved && !inputs.shutterPaths)
    throw Error("post-process: the curved motion path needs the G-buffer's shutter paths");
  // The linear gather is built without the curved path's code: on lavapipe that code runs for
  // every sample whether or not the flag asks for it.
  std::unique_ptr<vk::ComputeKernel>& kernel = kernels_[outsideMask ? 1 : 0][curved ? 1 : 0];
  if (!kernel) {
    uint32_t specialization[HMB_SPEC_GATHER_CURVED_PATH + 1] = {};
    specialization[HMB_SPEC_GATHER_OUTSIDE_MASK] = outsideMask ? 1u : 0u;
    specialization[HMB_SPEC_GATHER_CURVED_PATH] = curved ? 1u : 0u;
    kernel = std::make_unique<vk::ComputeKernel>(context_, "mblur/gather", sizeof(gpu::GatherParams), specialization);
  }
  gpu::GatherParams params = gatherParams(settings, inputs.width, inputs.height);
  if (curved) params.flags |= HMB_GATHER_FLAG_CURVED_PATH;
  vk::Bindings bindings = filterBindings(inputs, neighborMax, output);
  bindings.push_back({HMB_GATHER_BINDING_MASK, &mask});
  frame.dispatch(kName, *kernel, bindings, params,
                 {vk::groupsFor(inputs.width, HMB_GATHER_GROUP_X), vk::groupsFor(inputs.height, HMB_GATHER_GROUP_Y), 1});
}

}  // namespace hmb::passes
