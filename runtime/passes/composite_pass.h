// Host side of kernels/hybrid/composite.comp: the hybrid's final image, the raster layer's
// gather with the blurred background composited in at mask pixels (coverage or weights).
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/passes/hybrid_settings.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/post_process_settings.h"
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
  // read at mask pixels. output: width * height vec4. The coverage form needs the adapted range.
  void record(vk::FrameRecorder& frame, const ImageLayer& raster, const vk::Buffer& neighborMax,
              const vk::Buffer& mask, const vk::Buffer& background, const vk::Buffer& output,
              const PostProcessSettings& settings, HybridComposite composite, uint32_t width, uint32_t height) const;

 private:
  const vk::Context& context_;
  vk::ComputeKernel coverage_;  // the default form; the weights form is built on first use
  mutable std::unique_ptr<vk::ComputeKernel> weights_;
};

}  // namespace hmb::passes
