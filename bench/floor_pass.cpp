#include "bench/floor_pass.h"

#include <vector>

#include <glm/glm.hpp>

#include "hmblur/error.h"
#include "kernels/debug/floor_pass.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::bench {

FloorPass::FloorPass(const vk::Context& context, uint32_t width, uint32_t height)
    : kernel_(context, kernels::kernel("debug/floor_pass")),
      input_(vk::uploadedBuffer(context, std::vector<glm::uvec4>(size_t(width) * height, glm::uvec4(7u)),
                                "floor input")),
      output_(context, uint64_t(width) * height * sizeof(glm::uvec4), vk::MemoryUse::Device, "floor output"),
      width_(width),
      height_(height) {}

void FloorPass::record(vk::FrameRecorder& frame) const {
  frame.dispatch(kName, kernel_, {{HMB_FLOOR_BINDING_INPUT, &input_}, {HMB_FLOOR_BINDING_OUTPUT, &output_}},
                 gpu::FloorParams{width_, height_, 0, 0},
                 {vk::groupsFor(width_, HMB_FLOOR_GROUP_X), vk::groupsFor(height_, HMB_FLOOR_GROUP_Y), 1});
}

double FloorPass::run(vk::FrameRecorder& frame) const {
  frame.begin();
  record(frame);
  const vk::FrameTimings timings = frame.submitAndWait();
  for (const vk::PassTiming& pass : timings.passes)
    if (pass.name == kName && pass.milliseconds) return *pass.milliseconds;
  throw Error("the device gives no timestamps: the floor pass cannot be timed");
}

std::vector<double> FloorPass::time(vk::FrameRecorder& frame, int warmup, int repeats) const {
  std::vector<double> ms;
  for (int i = 0; i < warmup + repeats; ++i) {
    const double t = run(frame);
    if (i >= warmup) ms.push_back(t);
  }
  return ms;
}

}  // namespace hmb::bench
