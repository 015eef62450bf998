#include "runtime/passes/background_gather_pass.h"

#include <cstddef>
#include <span>
#include <vector>

#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "kernels/mblur/mblur_layout.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/reveal/reveal_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

BackgroundGatherPass::BackgroundGatherPass(const vk::Context& context)
    : kernels_(context, kernels::kernel("reveal/gather_background")) {}

void BackgroundGatherPass::record(vk::FrameRecorder& frame, const ImageLayer& raster, const ImageLayer& revealed,
                                  const vk::Buffer& neighborMax, const vk::Buffer& mask, const vk::Buffer& list,
                                  const vk::Buffer& counters, const vk::Buffer& output,
                                  const gpu::GatherParams& blur, const vk::Buffer* shutterPaths,
                                  const vk::Buffer* coverage) const {
  static_assert(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y == HMB_MASK_LIST_GROUP);
  if (coverage && (blur.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) == 0u)
    throw Error("gather-background: the coverage composite needs the adapted range");
  // Built for the frame's path, range and use alone (kernels/reveal/reveal_layout.h).
  static_assert(HMB_SPEC_BACKGROUND_GATHER_CURVED_PATH == 0 && HMB_SPEC_BACKGROUND_GATHER_ADAPTED_RANGE == 1 &&
                HMB_SPEC_BACKGROUND_GATHER_COVERAGE == 2);
  const vk::ComputeKernel& kernel =
      kernels_.with({(blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u,
                     (blur.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) != 0u, coverage != nullptr});
  vk::Bindings bindings = {{HMB_BACKGROUND_GATHER_BINDING_NEIGHBOR_MAX, &neighborMax},
                           {HMB_BACKGROUND_GATHER_BINDING_MASK, &mask},
                           {HMB_BACKGROUND_GATHER_BINDING_LIST, &list},
                           {HMB_BACKGROUND_GATHER_BINDING_COUNTERS, &counters},
                           {HMB_BACKGROUND_GATHER_BINDING_OUTPUT, &output},
                           // Read only along curved paths; any texel buffer stands in otherwise.
                           {HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS, shutterPaths ? shutterPaths : &raster.samples()},
                           // Read with the coverage composite only; any texel buffer stands in otherwise.
                           {HMB_BACKGROUND_GATHER_BINDING_COVERAGE, coverage ? coverage : &raster.samples()}};
  raster.bind(bindings, HMB_BACKGROUND_GATHER_BINDING_RASTER, kernel.bindsByAddress());
  revealed.bind(bindings, HMB_BACKGROUND_GATHER_BINDING_REVEALED, kernel.bindsByAddress());
  frame.dispatchIndirect(kName, kernel, bindings, blur, counters,
                         gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_MASK));
}

}  // namespace hmb::passes
