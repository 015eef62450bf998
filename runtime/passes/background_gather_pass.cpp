#include "runtime/passes/background_gather_pass.h"

#include <cstddef>
#include <span>
#include <vector>

#include "kernels/hybrid/hybrid_layout.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

BackgroundGatherPass::BackgroundGatherPass(const vk::Context& context)
    : kernel_(context, "hybrid/gather_background", sizeof(gpu::GatherParams)) {}

void BackgroundGatherPass::record(vk::FrameRecorder& frame, const ImageLayer& raster, const ImageLayer& revealed,
                                  const vk::Buffer& neighborMax, const vk::Buffer& mask, const vk::Buffer& list,
                                  const vk::Buffer& counters, const vk::Buffer& output,
                                  const gpu::GatherParams& blur) const {
  static_assert(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y == HMB_MASK_LIST_GROUP);
  std::vector<const vk::Buffer*> bindings = {&neighborMax, &mask, &list, &counters, &output};
  raster.appendBindings(bindings, kernel_.bindsByAddress());
  revealed.appendBindings(bindings, kernel_.bindsByAddress());
  frame.dispatchIndirect(kName, kernel_, bindings, std::as_bytes(std::span(&blur, 1)), counters,
                         offsetof(gpu::RayMaskCounters, maskDispatchX));
}

}  // namespace hmb::passes
