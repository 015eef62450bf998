#include "runtime/passes/gbuffer_stage.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "kernels/shared/scene_layout.h"
#include "runtime/deformed_vertices.h"
#include "runtime/frame_plan.h"
#include "runtime/gpu_scene.h"

namespace hmb::passes {

GBufferStage::GBufferStage(const vk::Context& context, VisibilityScheme scheme)
    : context_(context), transform_(context), rasterize_(context, scheme), resolve_(context) {}

void GBufferStage::plan(FramePlan& plan, const GpuScene& scene) const {
  if (scene.deforms())
    plan.run(DeformedVertices::kName);
  else
    plan.skip(DeformedVertices::kName, kNoDeformationReason);
  plan.run(TransformVerticesPass::kName);
  rasterize_.plan(plan);
  plan.run(ResolveGBufferPass::kName);
  for (const char* name : {ShutterPathPass::kTransformName, ShutterPathPass::kResolveName}) {
    if (shutterPaths_)
      plan.run(name);
    else
      plan.skip(name, noPathsReason_);
  }
}

void GBufferStage::prepare(const GpuScene& scene, uint32_t width, uint32_t height,
                           std::optional<ShutterPaths> shutterPaths, std::string_view noPathsReason) {
  shutterPaths_ = shutterPaths;
  noPathsReason_ = noPathsReason;
  const uint32_t vertices = std::max(1u, scene.instanceVertexCount());
  if (shutterPaths_) {
    if (!shutterPath_) shutterPath_ = std::make_unique<ShutterPathPass>(context_);
    if (vertices > pathVertexCapacity_) {
      clipMid_ = vk::Buffer(context_, uint64_t(vertices) * sizeof(glm::vec4), vk::MemoryUse::Device, "clip mid-shutter");
      clipOpen_ = vk::Buffer(context_, uint64_t(vertices) * sizeof(glm::vec4), vk::MemoryUse::Device, "clip shutter open");
      pathVertexCapacity_ = vertices;
    }
    // Two pixels a 16-byte record: rounded up to whole records for the texel view.
    const uint64_t pixels = (uint64_t(width) * height + 1) / 2 * 2;
    if (pixels > pathPixelCapacity_) {
      paths_ = vk::Buffer(context_, pixels * sizeof(glm::uvec2), vk::MemoryUse::Device, "shutter paths");
      pathPixelCapacity_ = pixels;
    }
    if (shutterPaths_->clips.empty()) shutterPaths_->clips.push_back({});  // a scene without instances draws nothing
    if (shutterClips_.size() < shutterPaths_->clips.size() * sizeof(gpu::GpuShutterClip))
      shutterClips_ = vk::Buffer(context_, shutterPaths_->clips.size() * sizeof(gpu::GpuShutterClip),
                                 vk::MemoryUse::Device, "shutter clip transforms");
    shutterClips_.upload(std::span<const gpu::GpuShutterClip>(shutterPaths_->clips));
  }
  if (vertices > vertexCapacity_) {
    clipCurrent_ = vk::Buffer(context_, uint64_t(vertices) * sizeof(glm::vec4), vk::MemoryUse::Device, "clip current");
    clipPrevious_ = vk::Buffer(context_, uint64_t(vertices) * sizeof(glm::vec4), vk::MemoryUse::Device, "clip previous");
    vertexShading_ = vk::Buffer(context_, uint64_t(vertices) * sizeof(gpu::GpuVertexShading), vk::MemoryUse::Device,
                                "vertex shading");
    vertexCapacity_ = vertices;
  }
  if (size_.changesTo(width, height)) {
    const uint64_t pixels = uint64_t(width) * height;
    visibility_ = vk::Buffer(context_, RasterizePass::visibilityBytes(width, height), vk::MemoryUse::Device,
                             "visibility");
    layer_ = {};  // the old layer goes first: the two never take memory at once
    layer_ = ImageLayer::allocate(context_, pixels, "gbuffer");
    size_.madeFor(width, height);
  }
  rasterize_.reserve(scene.triangleCount(), width, height);
}

void GBufferStage::record(vk::FrameRecorder& frame, const GpuScene& scene) const {
  scene.recordFrameDeformation(frame);
  transform_.record(frame, scene, clipCurrent_, clipPrevious_, vertexShading_);
  const RasterInputs inputs{&scene.triangles(), &scene.instances(), &clipCurrent_, scene.triangleCount()};
  rasterize_.record(frame, inputs, visibility_, size_.width(), size_.height());
  resolve_.record(frame, scene, visibility_, clipCurrent_, clipPrevious_, vertexShading_, layer_, size_.width(), size_.height());
  if (shutterPaths_) {
    shutterPath_->recordTransform(frame, scene, shutterClips_, shutterPaths_->exposure, shutterPaths_->fps, clipMid_,
                                  clipOpen_);
    shutterPath_->recordResolve(frame, scene, visibility_, clipCurrent_, clipMid_, clipOpen_, paths_, size_.width(),
                                size_.height());
  }
}

}  // namespace hmb::passes
