// Host side of kernels/gbuffer/resolve_gbuffer.comp: visibility buffer -> G-buffer.
#pragma once

#include <cstdint>

#include "runtime/passes/shading_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb {
class GpuScene;
}

namespace hmb::passes {

// The G-buffer of a frame, one entry per pixel, row 0 at the top (layouts: gbuffer_layout.h).
struct GBufferTargets {
  const vk::Buffer* color = nullptr;        // vec4 linear RGB, a = 1
  const vk::Buffer* normalDepth = nullptr;  // vec4 world normal, w camera-space depth
  const vk::Buffer* velocity = nullptr;     // vec2 pixels per frame, y down
  const vk::Buffer* objectId = nullptr;     // uint, 0 = background
};

class ResolveGBufferPass {
 public:
  static constexpr const char* kName = "resolve-gbuffer";
  explicit ResolveGBufferPass(const vk::Context& context);
  void record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& visibility,
              const vk::Buffer& clipCurrent, const vk::Buffer& clipPrevious, const vk::Buffer& vertexShading,
              const GBufferTargets& targets,
              uint32_t width, uint32_t height) const;

 private:
  ShadingKernel kernel_;
};

}  // namespace hmb::passes
