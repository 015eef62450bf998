#include "runtime/passes/gather_pass.h"

#include <algorithm>
#include <cstddef>
#include <span>

#include "kernels/hybrid/hybrid_layout.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/error.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

GatherPass::GatherPass(const vk::Context& context)
    : kernel_(context, "mblur/gather", sizeof(gpu::GatherParams)),
      dummy_(vk::uploadedBuffer(context, std::vector<uint32_t>(4, 0u), "gather unused option")) {}

void GatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                        const GatherOptions& options, const vk::Buffer& output,
                        const PostProcessSettings& settings, std::string_view passName) const {
  if (options.background && (!options.mask || !options.objectId))
    throw Error("gather: the composite needs the mask and the object ids");
  if (options.background && options.composite == HybridComposite::Coverage && settings.range != GatherRange::Adapted)
    throw Error("gather: the coverage composite needs the adapted range");
  const bool overlay = options.overlayColor || options.overlayNormalDepth || options.overlayVelocity;
  if (overlay && !(options.overlayColor && options.overlayNormalDepth && options.overlayVelocity && options.mask))
    throw Error("gather: the overlay needs its colour, normal-depth and velocity and the mask");
  if (overlay && options.background) throw Error("gather: the overlay and the composite do not mix");
  if (bool(options.pixelList) != bool(options.listCounters))
    throw Error("gather: pixel-list mode needs both the list and its counters");
  const TileGrid grid = tileGridFor(inputs.width, inputs.height, settings.tileSize);
  uint32_t flags = 0;
  if (settings.range == GatherRange::Adapted) flags |= HMB_GATHER_FLAG_ADAPTED_RANGE;
  if (overlay)
    flags |= HMB_GATHER_FLAG_OVERLAY;
  else if (options.mask)
    flags |= HMB_GATHER_FLAG_USE_MASK;
  if (options.pixelList) flags |= HMB_GATHER_FLAG_PIXEL_LIST;
  if (options.background)
    flags |= options.composite == HybridComposite::Weights ? HMB_GATHER_FLAG_COMPOSITE_WEIGHTS
                                                           : HMB_GATHER_FLAG_COMPOSITE_COVERAGE;
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
                                 float(std::max(inputs.width, inputs.height)),
                                 0,
                                 0};
  auto orDummy = [&](const vk::Buffer* b) { return b ? b : &dummy_; };
  const vk::Buffer* buffers[] = {inputs.color,
                                 inputs.normalDepth,
                                 inputs.velocity,
                                 &neighborMax,
                                 orDummy(options.mask),
                                 &output,
                                 orDummy(options.pixelList),
                                 orDummy(options.listCounters),
                                 orDummy(options.background),
                                 orDummy(options.objectId),
                                 orDummy(options.overlayColor),
                                 orDummy(options.overlayNormalDepth),
                                 orDummy(options.overlayVelocity)};
  static_assert(sizeof(buffers) / sizeof(buffers[0]) == HMB_GATHER_BINDING_COUNT);
  static_assert(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y == HMB_MASK_LIST_GROUP);
  const auto push = std::as_bytes(std::span<const gpu::GatherParams>(&params, 1));
  if (options.pixelList)
    frame.dispatchIndirect(passName, kernel_, buffers, push, *options.listCounters,
                           offsetof(gpu::RayMaskCounters, maskDispatchX));
  else
    frame.dispatch(passName, kernel_, buffers, push,
                   {vk::groupsFor(inputs.width, HMB_GATHER_GROUP_X), vk::groupsFor(inputs.height, HMB_GATHER_GROUP_Y), 1});
}

}  // namespace hmb::passes
