// Host side of kernels/ray_mask/mask_coverage.comp and list_mask_blocks.comp: with the coverage
// composite, the ray mask's last passes. At each pixel the range check listed, mask_coverage
// finds the composite's alpha and foreground colour, writes the pixel's mask value and sets its
// bit in its block's words (dispatched indirectly from the range check's count);
// list_mask_blocks then lists the mask's pixels block by block, for the reveal (the list's
// front) or for the composite alone (its back).
#pragma once

#include "kernels/ray_mask/ray_mask_layout.h"
#include "runtime/passes/gather_filter.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/kernel_variants.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

class MaskCoveragePass {
 public:
  static constexpr const char* kName = "ray-mask-coverage";
  static constexpr const char* kListName = "ray-mask-list";
  explicit MaskCoveragePass(const vk::Context& context);
  // layer: the G-buffer (samples, surfaces; the shutter paths along curved paths). pixels: the
  // range check's mask pixels (list_range_mask's list), counters: their coverageCount and the
  // dispatch sized from it. coverage: width * height vec4, mask: the ray mask (2 bits a pixel),
  // HMB_MASK_UNREVEALED at the listed pixels, which it turns to HMB_MASK_REVEALED where a sample
  // meets the background.
  // blockBits: maskBlockBitsBytes, filled with 0 before. list: the mask's (RayMaskStage's);
  // counters' maskCount and unrevealedCount count its two ends. params: the mask's (the frame's
  // blur).
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& layer, const vk::Buffer& pixels,
              const vk::Buffer& counters, const vk::Buffer& coverage, const vk::Buffer& mask,
              const vk::Buffer& blockBits, const vk::Buffer& list, const gpu::RayMaskParams& params) const;

 private:
  vk::KernelVariants kernels_;  // mask_coverage by path
  vk::ComputeKernel listKernel_;
};

// The bytes of a width x height image's block bits (HMB_MASK_COVERAGE_BINDING_BLOCK_BITS).
uint64_t maskBlockBitsBytes(uint32_t width, uint32_t height);

}  // namespace hmb::passes
