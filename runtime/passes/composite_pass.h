// Host side of kernels/hybrid/composite.comp: the hybrid's final image, the raster layer's
// gather with the blurred background composited in at mask pixels (coverage or weights).
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/passes/hybrid_settings.h"
#include "runtime/passes/image_layer.h"
#include "kernels/mblur/mblur_layout.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

class CompositePass {
 public:
  static constexpr const char* kName = "gather-composite";
  explicit CompositePass(const vk::Context& context);
  // neighborMax: the raster's. mask: RayMaskStage's. background: BackgroundGatherPass's output,
  // read at mask pixels. output: width * height vec4. blur: the frame's (gatherParams(), with the
  // hybrid's mask weights). The coverage form needs the adapted range.
  void record(vk::FrameRecorder& frame, const ImageLayer& raster, const vk::Buffer& neighborMax,
              const vk::Buffer& mask, const vk::Buffer& background, const vk::Buffer& output,
              const gpu::GatherParams& blur, HybridComposite composite,
              const vk::Buffer* shutterPaths = nullptr) const;  // the raster's, along curved paths

 private:
  const vk::Context& context_;
  vk::ComputeKernel coverage_;  // the default form; the weights form is built on first use
  mutable std::unique_ptr<vk::ComputeKernel> weights_;
};

}  // namespace hmb::passes
