// Host side of kernels/mblur/gather_jimenez.comp: the Jimenez 2014 filter (the paper's UE4-like
// baseline). Its tiles come from TileMaxPass / NeighborMaxPass at settings.jimenezTileSize with
// the centred velocity scale.
#pragma once

#include <cstdint>
#include <string_view>

#include "runtime/passes/gather_pass.h"
#include "runtime/passes/post_process_settings.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class JimenezGatherPass {
 public:
  static constexpr const char* kName = "gather-jimenez";
  explicit JimenezGatherPass(const vk::Context& context);
  // neighborMax: grid at settings.jimenezTileSize; output: width * height vec4.
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
              const vk::Buffer& output, const PostProcessSettings& settings, std::string_view passName = kName) const;

 private:
  vk::ComputeKernel kernel_;
};

}  // namespace hmb::passes
