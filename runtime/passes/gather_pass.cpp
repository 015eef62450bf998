#include "runtime/passes/gather_pass.h"

#include "kernels/mblur/mblur_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

GatherPass::GatherPass(const vk::Context& context)
    : kernel_(context, "mblur/gather", HMB_GATHER_BINDING_COUNT, sizeof(gpu::GatherParams)),
      dummyMask_(vk::uploadedBuffer(context, std::vector<uint32_t>{0u}, "gather no-mask")) {}

void GatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                        const vk::Buffer* mask, const vk::Buffer& output, const PostProcessSettings& settings,
                        std::string_view passName) const {
  const TileGrid grid = tileGridFor(inputs.width, inputs.height, settings.tileSize);
  uint32_t flags = 0;
  if (settings.range == GatherRange::Adapted) flags |= HMB_GATHER_FLAG_ADAPTED_RANGE;
  if (mask) flags |= HMB_GATHER_FLAG_USE_MASK;
  const float velocityScale = gatherVelocityScale(settings.range, settings.exposure, settings.fps);
  const gpu::GatherParams params{inputs.width,
                                 inputs.height,
                                 settings.tileSize,
                                 grid.x,
                                 grid.y,
                                 settings.samples,
                                 settings.seed,
                                 flags,
                                 velocityScale,
                                 settings.softZExtent,
                                 settings.effectiveForegroundBoost(),
                                 settings.maskBackgroundBoost,
                                 settings.maskForegroundDivide,
                                 0,
                                 0,
                                 0};
  frame.dispatch(passName, kernel_,
                 {inputs.color, inputs.normalDepth, inputs.velocity, &neighborMax, mask ? mask : &dummyMask_, &output},
                 params,
                 {vk::groupsFor(inputs.width, HMB_GATHER_GROUP_X), vk::groupsFor(inputs.height, HMB_GATHER_GROUP_Y), 1});
}

}  // namespace hmb::passes
