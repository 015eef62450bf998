// Host side of kernels/mblur/gather_jimenez.comp: the Jimenez 2014 filter (the paper's UE4-like
// baseline; the "jimenez" filter), always centred.
#pragma once

#include <cstdint>
#include <string_view>

#include "hmblur/post_process_settings.h"
#include "runtime/passes/gather_filter.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class JimenezGatherPass final : public GatherFilter {
 public:
  static constexpr const char* kName = "gather-jimenez";
  explicit JimenezGatherPass(const vk::Context& context);
  std::string_view passName() const override { return kName; }
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
              const vk::Buffer& output, const PostProcessSettings& settings) const override;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
