// Host side of kernels/raster/transform_vertices.comp: clip-space positions of every instance
// vertex at the frame time and at the previous frame, and its world normal and uv.
#pragma once

#include <cstdint>

#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb {
class GpuScene;
}

namespace hmb::passes {

class TransformVerticesPass {
 public:
  static constexpr const char* kName = "transform-vertices";
  explicit TransformVerticesPass(const vk::Context& context);
  // Per instance vertex of the scene: clipCurrent, clipPrevious (vec4), shading (GpuVertexShading).
  void record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& clipCurrent,
              const vk::Buffer& clipPrevious, const vk::Buffer& shading) const;

 private:
  vk::ComputeKernel rigid_;     // every vertex at its mesh's position at both times
  vk::ComputeKernel deformed_;  // previous positions of their own (GpuScene::deforms)
};

}  // namespace hmb::passes
