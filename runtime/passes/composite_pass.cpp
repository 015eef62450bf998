#include "runtime/passes/composite_pass.h"

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
CompositePass::CompositePass(const vk::Context& context)
    : kernels_(context, kernels::kernel("reveal/composite")) {}

void CompositePass::record(vk::FrameRecorder& frame, const ImageLayer& raster, const vk::Buffer& neighborMax,
                           const vk::Buffer& list, const vk::Buffer& counters, const vk::Buffer& background,
                           const vk::Buffer& output, const gpu::GatherParams& blur, HybridComposite composite,
                           const vk::Buffer* shutterPaths, const vk::Buffer* coverage) const {
  static_assert(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y == HMB_MASK_LIST_GROUP);
  const bool coverageForm = composite == HybridComposite::Coverage;
  if (coverageForm && (blur.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) == 0u)
    throw Error("composite: the coverage form needs the adapted range");
  if (coverageForm && !coverage)
    throw Error("composite: the coverage form needs the mask's coverage (RayMaskStage::coverage)");
  // Built for the frame's path, range and form alone (kernels/reveal/reveal_layout.h).
  static_assert(HMB_SPEC_COMPOSITE_CURVED_PATH == 0 && HMB_SPEC_COMPOSITE_ADAPTED_RANGE == 1 &&
                HMB_SPEC_COMPOSITE_COVERAGE == 2);
  const vk::ComputeKernel& kernel =
      kernels_.with({(blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u,
                     (blur.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) != 0u, coverageForm});
  vk::Bindings bindings = {{HMB_COMPOSITE_BINDING_NEIGHBOR_MAX, &neighborMax},
                           {HMB_COMPOSITE_BINDING_LIST, &list},
                           {HMB_COMPOSITE_BINDING_COUNTERS, &counters},
                           {HMB_COMPOSITE_BINDING_BACKGROUND, &background},
                           {HMB_COMPOSITE_BINDING_OUTPUT, &output},
                           // Read only along curved paths; any texel buffer stands in otherwise.
                           {HMB_COMPOSITE_BINDING_SHUTTER_PATHS, shutterPaths ? shutterPaths : &raster.samples()},
                           // Read by the coverage form only; any texel buffer stands in otherwise.
                           {HMB_COMPOSITE_BINDING_COVERAGE, coverage ? coverage : &background}};
  raster.bind(bindings, HMB_COMPOSITE_BINDING_RASTER, kernel.bindsByAddress());
  // The weights form's mask is all at the list's front; the coverage form takes its back.
  frame.dispatchIndirect(kName, kernel, bindings, blur, counters,
                         coverageForm ? gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_UNREVEALED)
                                      : gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_MASK));
}

}  // namespace hmb::passes
