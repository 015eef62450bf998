// The G-buffer stage every method starts from: transform_vertices -> the compute rasterizer
// (RasterizePass) -> resolve_gbuffer, and for frames whose blur follows curved paths the
// shutter-path passes (ShutterPathPass). Owns the per-frame buffers between those passes.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hmblur/buffer.h"
#include "kernels/shared/scene_layout.h"
#include "runtime/passes/image_size.h"
#include "runtime/passes/pass_list.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/passes/resolve_gbuffer_pass.h"
#include "runtime/passes/shutter_path_pass.h"
#include "runtime/passes/transform_vertices_pass.h"

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

  // Whether the frame's blur follows curved paths: the stage then also writes each pixel's
  // path over the blur's shutter [t - E, t] (shutterPaths()). E: the blur's exposure (a time
  // slice's with time slices), fps the scene's rate, clips every instance's transforms at
  // t - E/2 and t - E (hmb::shutterClips).
  struct ShutterPaths {
    float exposure = 0.0f;
    float fps = 0.0f;
    std::vector<gpu::GpuShutterClip> clips;
  };
  // Sizes the buffers for this scene and resolution (reuses them when they fit).
  // noPathsReason: why the plan leaves the path passes out when shutterPaths is empty.
  void prepare(const GpuScene& scene, uint32_t width, uint32_t height,
               std::optional<ShutterPaths> shutterPaths = std::nullopt,
               std::string_view noPathsReason = kStraightPathsReason);
  void record(vk::FrameRecorder& frame, const GpuScene& scene) const;

  const RasterizePass& rasterizer() const { return rasterize_; }
  RasterizePass& rasterizer() { return rasterize_; }
  const vk::Buffer& clipCurrent() const { return clipCurrent_; }
  const vk::Buffer& clipPrevious() const { return clipPrevious_; }
  const vk::Buffer& vertexShading() const { return vertexShading_; }  // gpu::GpuVertexShading per instance vertex
  const vk::Buffer& visibility() const { return visibility_; }
  const ImageLayer& layer() const { return layer_; }
  // vec4 per instance vertex at mid-shutter and shutter open (frames with paths only).
  const vk::Buffer& clipMid() const { return clipMid_; }
  const vk::Buffer& clipOpen() const { return clipOpen_; }
  // uvec2 per pixel (kernels/gbuffer/gbuffer_layout.h), or null when the frame has no paths.
  const vk::Buffer* shutterPaths() const { return shutterPaths_ ? &paths_ : nullptr; }
  // Bytes per pixel of the per-pixel buffers: visibility, the layer's samples and surfaces,
  // and the paths when the frame has them.
  double bytesPerPixel(uint32_t width, uint32_t height) const {
    const uint64_t paths = shutterPaths_ ? paths_.size() : 0;
    return double(visibility_.size() + layer_.bytes() + paths) / (double(width) * height);
  }

 private:
  struct Frame {
    const GpuScene* scene = nullptr;
  };

  const vk::Context& context_;
  PassList<Frame> passes_;
  TransformVerticesPass transform_;
  RasterizePass rasterize_;
  ResolveGBufferPass resolve_;
  std::unique_ptr<ShutterPathPass> shutterPath_;  // made for the first frame that needs it
  std::optional<ShutterPaths> shutterPaths_;
  std::string noPathsReason_;
  ImageSize size_;
  uint32_t vertexCapacity_ = 0, pathVertexCapacity_ = 0;
  uint64_t pathPixelCapacity_ = 0;
  vk::Buffer clipCurrent_, clipPrevious_, vertexShading_;
  vk::Buffer clipMid_, clipOpen_, paths_, shutterClips_;
  vk::Buffer visibility_;
  ImageLayer layer_;
};

}  // namespace hmb::passes
