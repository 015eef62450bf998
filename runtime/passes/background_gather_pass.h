// Host side of kernels/reveal/gather_background.comp: the hybrid's background layer (the raster
// with the revealed surfaces in its place where the mask says so) blurred at the ray mask's
// listed pixels (the list's front), dispatched indirectly from its length; with the coverage
// composite, blended under the mask's foreground into the hybrid's image there.
#pragma once

#include "kernels/mblur/mblur_layout.h"
#include "runtime/passes/image_layer.h"
#include "runtime/vulkan/kernel_variants.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

class BackgroundGatherPass {
 public:
  static constexpr const char* kName = "gather-background";
  explicit BackgroundGatherPass(const vk::Context& context);
  // neighborMax: the raster's (PostProcessStage). mask, list, counters: RayMaskStage's.
  // output: width * height vec4, written at the list's front: the blurred background, or with
  // `coverage` (RayMaskStage::coverage(): mask_coverage's alpha and foreground) the hybrid's
  // image (the adapted range only). blur: the frame's (gatherParams()).
  void record(vk::FrameRecorder& frame, const ImageLayer& raster, const ImageLayer& revealed,
              const vk::Buffer& neighborMax, const vk::Buffer& mask, const vk::Buffer& list,
              const vk::Buffer& counters, const vk::Buffer& output, const gpu::GatherParams& blur,
              const vk::Buffer* shutterPaths = nullptr,  // the raster's, along curved paths
              const vk::Buffer* coverage = nullptr) const;

 private:
  vk::KernelVariants kernels_;  // by path, range and use
};

}  // namespace hmb::passes
