// Host side of kernels/hybrid/mask_coverage.comp: with the coverage composite, the ray mask's
// last pass. At each pixel the range check listed it finds the composite's alpha and
// foreground colour, writes the pixel's mask value, and lists it for the reveal (the list's
// front) or for the composite alone (its back). Dispatched indirectly from the range check's
// count.
#pragma once

#include "kernels/hybrid/hybrid_layout.h"
#include "runtime/passes/post_process_filter.h"
#include "runtime/vulkan/kernel_variants.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

class MaskCoveragePass {
 public:
  static constexpr const char* kName = "ray-mask-coverage";
  explicit MaskCoveragePass(const vk::Context& context);
  // layer: the G-buffer (samples, surfaces; the shutter paths along curved paths). pixels: the
  // range check's list, counters: its coverageCount and the dispatch sized from it.
  // coverage: width * height vec4, mask: uint per pixel, list: the mask's (RayMaskStage's),
  // written at the listed pixels. params: the mask's (the frame's blur).
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& layer, const vk::Buffer& pixels,
              const vk::Buffer& counters, const vk::Buffer& coverage, const vk::Buffer& mask, const vk::Buffer& list,
              const gpu::RayMaskParams& params) const;

 private:
  vk::KernelVariants kernels_;  // by path
};

}  // namespace hmb::passes
