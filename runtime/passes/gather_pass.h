// Host side of kernels/mblur/gather.comp: the post-process gather, McGuire et al. 2012's
// reconstruction with the paper's weights, centred or adapted range.
#pragma once

#include <cstdint>
#include <string_view>

#include "kernels/mblur/mblur_layout.h"
#include "runtime/passes/post_process_settings.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

// One layer to blur, width * height entries each, row 0 at the top.
struct MotionBlurInputs {
  const vk::Buffer* color = nullptr;        // vec4 linear
  const vk::Buffer* normalDepth = nullptr;  // vec4, w camera-space depth
  const vk::Buffer* velocity = nullptr;     // vec2 pixels per frame, y down
  uint32_t width = 0;
  uint32_t height = 0;
};

// The parameters every McGuire gather of a width x height image takes from the settings (the
// post-process gather, the hybrid's background gather and composite).
gpu::GatherParams gatherParams(const PostProcessSettings& settings, uint32_t width, uint32_t height);

class GatherPass {
 public:
  static constexpr const char* kName = "gather";
  explicit GatherPass(const vk::Context& context);
  // neighborMax: from NeighborMaxPass at settings.tileSize with settings.velocityScale().
  // output: width * height vec4. Uses the McGuire fields of settings whatever settings.filter.
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
              const vk::Buffer& output, const PostProcessSettings& settings) const;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
