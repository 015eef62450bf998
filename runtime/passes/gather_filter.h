// What a post-process filter's gather is to the stage that runs it (post_process_filter.h lists
// the filters): the layer it blurs, what its kernel binds, and its pass's plan and recording.
#pragma once

#include <cstdint>
#include <string_view>

#include "hmblur/post_process_filter.h"
#include "runtime/vulkan/binding.h"

namespace hmb {
class FramePlan;
}  // namespace hmb

namespace hmb::vk {
class FrameRecorder;
}  // namespace hmb::vk

namespace hmb::passes {

struct PostProcessSettings;

// One layer to blur (kernels/shared/layer_layout.h), width * height pixels, row 0 at the top: its
// samples (colour, depth, velocity: what the gathers read), surfaces (normal, object id, depth:
// what the hybrid's ray mask reads) and velocities (floats, which tile-max ranks).
struct MotionBlurInputs {
  const vk::Buffer* samples = nullptr;
  const vk::Buffer* surfaces = nullptr;
  const vk::Buffer* velocities = nullptr;
  uint32_t width = 0;
  uint32_t height = 0;
  // Each pixel's path over the shutter (kernels/gbuffer/gbuffer_layout.h), for the curved
  // motion path; null: the gathers follow straight lines.
  const vk::Buffer* shutterPaths = nullptr;
};

// What every filter's kernel binds (kernels/mblur/filter_bindings.glsl).
vk::Bindings filterBindings(const MotionBlurInputs& inputs, const vk::Buffer& neighborMax, const vk::Buffer& output);

class GatherFilter {
 public:
  virtual ~GatherFilter() = default;
  // Its pass in the frame plan.
  virtual std::string_view passName() const = 0;
  // Its passes in the frame plan: passName() and any it records beside it.
  virtual void plan(FramePlan& plan) const;
  // neighborMax: the tile passes' at settings.effectiveTileSize() and settings.velocityScale();
  // output: width * height vec4.
  virtual void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                      const vk::Buffer& output, const PostProcessSettings& settings) const = 0;
};

}  // namespace hmb::passes
