// Host side of the curved motion path's two kernels: raster/transform_shutter_path.comp (each
// instance vertex's clip position at mid-shutter and shutter open) and
// gbuffer/resolve_shutter_path.comp (each pixel's path over the shutter, the "paths" buffer:
// gbuffer_layout.h). The G-buffer stage runs them only for frames that gather along that path.
#pragma once

#include <cstdint>
#include <string_view>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb {
class GpuScene;
}

namespace hmb::passes {

// Why a frame leaves both passes out: its blur follows straight lines (a setting, not the
// scene), or nothing moves on screen (the scene at this frame).
inline constexpr std::string_view kStraightPathsReason =
    "the blur follows straight lines (motion-path linear, or a method without curved paths)";
inline constexpr std::string_view kStillPathsReason =
    "nothing moves on screen at this frame: every path is a point, and the blur is left out";

class ShutterPathPass {
 public:
  static constexpr const char* kTransformName = "transform-shutter-path";
  static constexpr const char* kResolveName = "resolve-shutter-path";
  explicit ShutterPathPass(const vk::Context& context);

  // clips: gpu::GpuShutterClip per instance (hmb::shutterClips); clipMid, clipOpen: vec4 per
  // instance vertex; exposure: the blur's, fps the scene's frame rate.
  void recordTransform(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& clips, float exposure,
                       float fps, const vk::Buffer& clipMid, const vk::Buffer& clipOpen) const;
  // paths: uvec2 per pixel.
  void recordResolve(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& visibility,
                     const vk::Buffer& clipCurrent, const vk::Buffer& clipMid, const vk::Buffer& clipOpen,
                     const vk::Buffer& paths, uint32_t width, uint32_t height) const;

 private:
  vk::ComputeKernel rigid_;
  vk::ComputeKernel deformed_;
  vk::ComputeKernel resolve_;
};

}  // namespace hmb::passes
