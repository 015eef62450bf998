#include "runtime/passes/mask_coverage_pass.h"

#include <cstddef>
#include <cstdint>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

MaskCoveragePass::MaskCoveragePass(const vk::Context& context)
    : kernels_(context, kernels::kernel("ray_mask/mask_coverage")),
      listKernel_(context, kernels::kernel("ray_mask/list_mask_blocks")) {}

uint64_t maskBlockBitsBytes(uint32_t width, uint32_t height) {
  return uint64_t(HMB_MASK_BLOCKS_ACROSS(width)) * HMB_MASK_BLOCKS_ACROSS(height) * 4 * sizeof(uint32_t);  // uvec4 each
}

void MaskCoveragePass::record(vk::FrameRecorder& frame, const MotionBlurInputs& layer, const vk::Buffer& pixels,
                              const vk::Buffer& counters, const vk::Buffer& coverage, const vk::Buffer& mask,
                              const vk::Buffer& blockBits, const vk::Buffer& list,
                              const gpu::RayMaskParams& params) const {
  if (blockBits.size() < maskBlockBitsBytes(params.blur.width, params.blur.height))
    throw Error("mask coverage: the block bits are too small for the image");
  if (!layer.samples || !layer.surfaces) throw Error("mask coverage: no G-buffer");
  const bool curved = (params.blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u;
  if (curved && !layer.shutterPaths) throw Error("mask coverage: the curved motion path needs the shutter paths");
  // Built with the curved path's code only where the frame takes it.
  static_assert(HMB_SPEC_MASK_COVERAGE_CURVED_PATH == 0);
  frame.dispatchIndirect(kName, kernels_.with({curved}),
                         {{HMB_MASK_COVERAGE_BINDING_SAMPLES, layer.samples},
                          {HMB_MASK_COVERAGE_BINDING_SURFACES, layer.surfaces},
                          // Read only along curved paths; any texel buffer stands in otherwise.
                          {HMB_MASK_COVERAGE_BINDING_SHUTTER_PATHS, curved ? layer.shutterPaths : layer.samples},
                          {HMB_MASK_COVERAGE_BINDING_PIXELS, &pixels},
                          {HMB_MASK_COVERAGE_BINDING_COUNTERS, &counters},
                          {HMB_MASK_COVERAGE_BINDING_COVERAGE, &coverage},
                          {HMB_MASK_COVERAGE_BINDING_MASK, &mask},
                          {HMB_MASK_COVERAGE_BINDING_BLOCK_BITS, &blockBits}},
                         params, counters, gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_COVERAGE));
  // A lane per block of the image.
  const uint32_t blocks = HMB_MASK_BLOCKS_ACROSS(params.blur.width) * HMB_MASK_BLOCKS_ACROSS(params.blur.height);
  frame.dispatch(kListName, listKernel_,
                 {{HMB_LIST_MASK_BLOCKS_BINDING_BLOCK_BITS, &blockBits},
                  {HMB_LIST_MASK_BLOCKS_BINDING_COUNTERS, &counters},
                  {HMB_LIST_MASK_BLOCKS_BINDING_LIST, &list}},
                 params, vk::foldedGroups(vk::groupsFor(blocks, HMB_LIST_MASK_BLOCKS_GROUP)));
}

}  // namespace hmb::passes
