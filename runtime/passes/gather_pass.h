// Host side of kernels/mblur/gather.comp: McGuire et al. 2012's reconstruction with the paper's
// weights, centred or adapted range, optional mask (the hybrid method's raster and revealed
// layers run it too, under their own pass names).
#pragma once

#include <cstdint>
#include <string_view>

#include "runtime/passes/hybrid_settings.h"
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

// What a gather may read beside its layer; all optional.
struct GatherOptions {
  const vk::Buffer* mask = nullptr;  // width * height uint (0/1): the mask boosts apply inside (or the overlay)
  // The hybrid composite inside the mask (needs mask): width * height vec4, the blurred
  // revealed background, read at mask pixels.
  const vk::Buffer* background = nullptr;
  const vk::Buffer* objectId = nullptr;  // composite: width * height uint, the layer's object ids
  HybridComposite composite = HybridComposite::Coverage;
  // Pixel-list mode: only these pixels are gathered (and written), dispatched indirectly from
  // a RayMaskCounters buffer (kernels/hybrid/hybrid_layout.h: length, then the dispatch).
  const vk::Buffer* pixelList = nullptr;
  const vk::Buffer* listCounters = nullptr;
  // Overlay (needs mask; no mask boosts): where the mask is HMB_MASK_REVEALED, the layer reads
  // these instead of its own colour, normal-depth and velocity.
  const vk::Buffer* overlayColor = nullptr;
  const vk::Buffer* overlayNormalDepth = nullptr;
  const vk::Buffer* overlayVelocity = nullptr;
};

class GatherPass {
 public:
  static constexpr const char* kName = "gather";
  explicit GatherPass(const vk::Context& context);
  // neighborMax: from NeighborMaxPass at settings.tileSize with settings.velocityScale().
  // mask: width * height uint (0/1) or nullptr (no mask: a dummy buffer is bound).
  // output: width * height vec4. Uses the McGuire fields of settings whatever settings.filter.
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
              const vk::Buffer* mask, const vk::Buffer& output, const PostProcessSettings& settings,
              std::string_view passName = kName) const {
    record(frame, inputs, neighborMax, GatherOptions{mask}, output, settings, passName);
  }
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
              const GatherOptions& options, const vk::Buffer& output, const PostProcessSettings& settings,
              std::string_view passName = kName) const;

 private:
  vk::ComputeKernel kernel_;
  vk::Buffer dummy_;  // bound where an option is not used
};

}  // namespace hmb::passes
