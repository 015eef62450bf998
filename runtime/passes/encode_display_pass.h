// Host side of kernels/output/encode_display.comp: the display image every PNG and metric uses.
#pragma once

#include <cstdint>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class EncodeDisplayPass {
 public:
  static constexpr const char* kName = "encode-display";
  explicit EncodeDisplayPass(const vk::Context& context);
  // linear: width * height vec4; rgba8: width * height uint (R in the low byte).
  void record(vk::FrameRecorder& frame, const vk::Buffer& linear, const vk::Buffer& rgba8, uint32_t width,
              uint32_t height) const;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
