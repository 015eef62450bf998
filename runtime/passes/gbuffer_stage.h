// The G-buffer stage every method starts from: transform_vertices -> the compute rasterizer
// (RasterizePass) -> resolve_gbuffer. Owns the per-frame buffers between those passes.
#pragma once

#include <cstdint>

#include "runtime/passes/image_size.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/passes/resolve_gbuffer_pass.h"
#include "runtime/passes/transform_vertices_pass.h"
#include "runtime/vulkan/buffer.h"

namespace hmb {
class FramePlan;
class GpuScene;
}

namespace hmb::passes {

class GBufferStage {
 public:
  GBufferStage(const vk::Context& context, VisibilityScheme scheme);

  // Deforms the scene's skinned and morphing meshes first when it has any.
  void plan(FramePlan& plan, const GpuScene& scene) const;

  // Sizes the buffers for this scene and resolution (reuses them when they fit).
  void prepare(const GpuScene& scene, uint32_t width, uint32_t height);
  void record(vk::FrameRecorder& frame, const GpuScene& scene) const;

  const RasterizePass& rasterizer() const { return rasterize_; }
  RasterizePass& rasterizer() { return rasterize_; }
  const vk::Buffer& clipCurrent() const { return clipCurrent_; }
  const vk::Buffer& clipPrevious() const { return clipPrevious_; }
  const vk::Buffer& vertexShading() const { return vertexShading_; }  // gpu::GpuVertexShading per instance vertex
  const vk::Buffer& visibility() const { return visibility_; }
  const ImageLayer& layer() const { return layer_; }
  // Bytes per pixel of the per-pixel buffers: visibility, the layer's samples and surfaces.
  double bytesPerPixel(uint32_t width, uint32_t height) const {
    return double(visibility_.size() + layer_.bytes()) / (double(width) * height);
  }

 private:
  const vk::Context& context_;
  TransformVerticesPass transform_;
  RasterizePass rasterize_;
  ResolveGBufferPass resolve_;
  ImageSize size_;
  uint32_t vertexCapacity_ = 0;
  vk::Buffer clipCurrent_, clipPrevious_, vertexShading_;
  vk::Buffer visibility_;
  ImageLayer layer_;
};

}  // namespace hmb::passes
