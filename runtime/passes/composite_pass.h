// Host side of kernels/reveal/composite.comp: the hybrid's final image at the ray mask's pixels
// over the post-process gather's image of the raster layer (every other pixel): with the weights
// composite at every mask pixel, the blurred background composited in; with the coverage
// composite at the pixels not revealed (BackgroundGatherPass blends the others).
#pragma once

#include <cstdint>

#include "hmblur/hybrid_settings.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/passes/image_layer.h"
#include "runtime/vulkan/kernel_variants.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

class CompositePass {
 public:
  static constexpr const char* kName = "composite";
  explicit CompositePass(const vk::Context& context);
  // neighborMax: the raster's. list, counters: RayMaskStage's (the mask's pixels, its front and
  // back; the indirect dispatch). background: BackgroundGatherPass's output, read at mask
  // pixels (weights form). output: width * height vec4, written at mask pixels. blur: the
  // frame's (gatherParams(), with the hybrid's mask weights). The coverage form needs the
  // adapted range.
  void record(vk::FrameRecorder& frame, const ImageLayer& raster, const vk::Buffer& neighborMax,
              const vk::Buffer& list, const vk::Buffer& counters, const vk::Buffer& background,
              const vk::Buffer& output, const gpu::GatherParams& blur, HybridComposite composite,
              const vk::Buffer* shutterPaths = nullptr,  // the raster's, along curved paths
              // the coverage form's: RayMaskStage::coverage() (mask_coverage's alpha and foreground)
              const vk::Buffer* coverage = nullptr) const;

 private:
  vk::KernelVariants kernels_;  // by path, range and form
};

}  // namespace hmb::passes
