// Host side of kernels/reveal/reveal_background.comp: the ray reveal (paper, section 3.2.2)
// of every pixel in the ray mask's list, dispatched indirectly from the list's length.
#pragma once

#include <cstdint>
#include <memory>

#include "hmblur/hybrid_settings.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/shading_kernel.h"

namespace hmb {
class GpuScene;
class TraceScene;
}

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class RevealPass {
 public:
  static constexpr const char* kName = "ray-reveal";
  // hits: how hits are shaded (null: the library's shading).
  explicit RevealPass(const vk::Context& context, const HitShading* hits = nullptr);
  // traceScene: shutter times set, the frame time first (the reveal traces at it). cameraRays: one gpu::PinholeCamera
  // at the frame time. raster: the G-buffer (its object ids, and its depths, where the rays start). list, counters:
  // RayMaskStage's.
  // output: written at the listed pixels.
  void record(vk::FrameRecorder& frame, const TraceScene& traceScene, const GpuScene& gpuScene,
              const vk::Buffer& cameraRays, const ImageLayer& raster, const vk::Buffer& list,
              const vk::Buffer& counters, const ImageLayer& output, uint32_t width, uint32_t height,
              const HybridSettings& settings) const;

 private:
  const vk::Context& context_;
  const HitShading* hits_;
  // A build per stop (reveal_layout.h's HMB_SPEC_REVEAL_STOP): the object-id one up front, the
  // luminance one on first use.
  ShadingKernel objectIdStop_;
  mutable std::unique_ptr<ShadingKernel> luminanceStop_;
};

}  // namespace hmb::passes
