// The floor every per-pixel pass is measured against (kernels/debug/floor_pass.comp): one
// 16-byte read and one write per pixel, timed in the same run as the passes it judges, so a
// pass's cost reads as a multiple of the least a full-screen pass costs on this device.
#pragma once

#include <cstdint>
#include <vector>

#include "hmblur/buffer.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Context;
class FrameRecorder;
}  // namespace hmb::vk

namespace hmb::bench {

class FloorPass {
 public:
  static constexpr const char* kName = "floor";
  FloorPass(const vk::Context& context, uint32_t width, uint32_t height);
  // Records the pass into `frame` (its time is the frame's pass named kName).
  void record(vk::FrameRecorder& frame) const;
  // Runs it alone once: device milliseconds.
  double run(vk::FrameRecorder& frame) const;
  // Runs it warmup + repeats times: the timed runs' milliseconds.
  std::vector<double> time(vk::FrameRecorder& frame, int warmup, int repeats) const;

 private:
  vk::ComputeKernel kernel_;
  vk::Buffer input_, output_;
  uint32_t width_, height_;
};

}  // namespace hmb::bench
