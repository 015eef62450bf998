// Host side of kernels/output/encode_display.comp: the display image every PNG and metric uses.
#pragma once

#include <cstdint>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

// What the display is encoded from.
enum class DisplaySource {
  LinearRgba,    // width * height vec4
  LayerSamples,  // an image layer's samples (kernels/shared/layer_layout.h): a G-buffer's colour
};

class EncodeDisplayPass {
 public:
  static constexpr const char* kName = "encode-display";
  explicit EncodeDisplayPass(const vk::Context& context);
  // input: width * height pixels as `source` says; rgba8: width * height uint (R in the low byte).
  void record(vk::FrameRecorder& frame, const vk::Buffer& input, const vk::Buffer& rgba8, uint32_t width,
              uint32_t height, DisplaySource source = DisplaySource::LinearRgba) const;

 private:
  vk::ComputeKernel linearKernel_, samplesKernel_;
};

}  // namespace hmb::passes
