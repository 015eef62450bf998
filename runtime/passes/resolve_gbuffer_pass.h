// Host side of kernels/gbuffer/resolve_gbuffer.comp: visibility buffer -> G-buffer.
#pragma once

#include <cstdint>

#include "runtime/passes/image_layer.h"
#include "runtime/passes/shading_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb {
class GpuScene;
}

namespace hmb::passes {

class ResolveGBufferPass {
 public:
  static constexpr const char* kName = "resolve-gbuffer";
  explicit ResolveGBufferPass(const vk::Context& context);
  void record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& visibility,
              const vk::Buffer& clipCurrent, const vk::Buffer& clipPrevious, const vk::Buffer& vertexShading,
              const ImageLayer& target, uint32_t width, uint32_t height) const;  // target keeps its velocities

 private:
  ShadingKernel kernel_;
};

}  // namespace hmb::passes
