// Host side of kernels/debug/test_pattern.comp.
#pragma once

#include <cstdint>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class TestPatternPass {
 public:
  static constexpr const char* kName = "test-pattern";
  explicit TestPatternPass(const vk::Context& context);
  // Writes width * height linear RGBA pixels (vec4) into `linear`.
  void record(vk::FrameRecorder& frame, const vk::Buffer& linear, uint32_t width, uint32_t height, float time) const;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
