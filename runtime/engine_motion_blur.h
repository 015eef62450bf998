// The library as an engine's motion-blur backend: post-process motion blur recorded into a
// command buffer the engine owns and submits, from the engine's own G-buffer to an output buffer
// the engine gives, on the engine's device (vk::Context(const AdoptedVulkan&, ...)). Nothing is
// read back and nothing waits; the device times of the passes are there once the engine's
// submission completed.
//
// The engine's buffers (storage-buffer usage; one entry per pixel, index y * width + x, row 0 at
// the top of the image):
//   colour    vec4 (16 bytes): linear RGB; alpha is ignored
//   depth     float: as EngineDepth says
//   velocity  vec2 (8 bytes): the pixel's screen motion over the last frame, in pixels, its
//             position now minus its position one frame (1 / fps) earlier, +x right, +y down
//             (the background's too: a turning camera moves it)
//   output    vec4: the blurred linear colour, alpha 1
// The blur spreads each pixel along its velocity over the exposure (PostProcessSettings:
// exposure and fps give the share of a frame the shutter is open; softZExtent is in the
// engine's camera-space depth units).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>

#include <vulkan/vulkan.h>

#include "runtime/passes/post_process_settings.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {

namespace vk {
class Context;
}

// How the engine's depth buffer holds depth.
struct EngineDepth {
  enum class Convention {
    CameraSpace,  // distance along the view axis, > 0 ahead of the camera
    StandardZ,    // perspective z/w in [0, 1]: 0 at near, 1 at far
    ReversedZ,    // perspective z/w in [0, 1]: 1 at near, 0 at far (far may be infinite)
  };
  Convention convention = Convention::CameraSpace;
  float near = 0.0f;  // the projection's planes, for the z/w conventions
  float far = std::numeric_limits<float>::infinity();
};

struct EngineGBuffer {
  VkBuffer color = VK_NULL_HANDLE;
  VkBuffer depth = VK_NULL_HANDLE;
  VkBuffer velocity = VK_NULL_HANDLE;
};

class EngineMotionBlur {
 public:
  // Validates the settings and the depth convention (hmb::Error, one line) and builds the kernels.
  EngineMotionBlur(const vk::Context& context, uint32_t width, uint32_t height,
                   const passes::PostProcessSettings& settings, EngineDepth depth = {});
  ~EngineMotionBlur();
  EngineMotionBlur(const EngineMotionBlur&) = delete;
  EngineMotionBlur& operator=(const EngineMotionBlur&) = delete;

  // Records the blur into `commandBuffer` (recording, outside a render pass, for a queue of the
  // context's family): a barrier after the engine's earlier writes, the passes, and a barrier
  // before its later commands. The frame recorded before must have completed on the device
  // (keep one EngineMotionBlur per frame in flight).
  void record(VkCommandBuffer commandBuffer, const EngineGBuffer& gbuffer, VkBuffer output);

  // The device time of each pass of the last recorded frame, once the engine's submission of it
  // completed (empty times when the queue has no timestamps).
  vk::FrameTimings timings() const;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  struct Passes;
  const vk::Context& context_;
  uint32_t width_, height_;
  EngineDepth depth_;
  std::unique_ptr<Passes> passes_;
};

}  // namespace hmb
