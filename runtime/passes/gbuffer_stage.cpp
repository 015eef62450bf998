#include "runtime/passes/gbuffer_stage.h"

#include <algorithm>

#include <glm/glm.hpp>

#include "hmblur/frame_plan.h"
#include "kernels/shared/scene_layout.h"
#include "runtime/device_scene/deformed_vertices.h"
#include "runtime/device_scene/gpu_scene.h"

namespace hmb::passes {

GBufferStage::GBufferStage(const vk::Context& context, VisibilityScheme scheme)
    : context_(context), passes_(context), transform_(context), rasterize_(context, scheme), resolve_(context) {
  const auto withoutPaths = [this](const Frame&) { return shutterPaths_ ? std::string() : noPathsReason_; };
  passes_
      .pass(
          DeformedVertices::kName,
          [](vk::FrameRecorder& frame, const Frame& f) { f.scene->recordFrameDeformation(frame); },
          [](const Frame& f) { return f.scene->deforms() ? std::string() : std::string(kNoDeformationReason); })
      .pass(TransformVerticesPass::kName,
            [this](vk::FrameRecorder& frame, const Frame& f) {
              transform_.record(frame, *f.scene, clipCurrent_, clipPrevious_, vertexShading_);
            })
      .group([this](FramePlan& plan, const Frame&) { rasterize_.plan(plan); },
             [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
               if (!plan.runs(RasterizePass::kSetup)) return;
               const RasterInputs inputs{&f.scene->triangles(), &f.scene->instances(), &clipCurrent_,
                                         f.scene->triangleCount()};
               rasterize_.record(frame, inputs, visibility_, size_.width(), size_.height());
             })
      .pass(ResolveGBufferPass::kName,
            [this](vk::FrameRecorder& frame, const Frame& f) {
              resolve_.record(frame, *f.scene, visibility_, clipCurrent_, clipPrevious_, vertexShading_, layer_,
                              size_.width(), size_.height());
            })
      .pass(
          ShutterPathPass::kTransformName,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            shutterPath_->recordTransform(frame, *f.scene, shutterClips_, shutterPaths_->exposure,
                                          shutterPaths_->fps, clipMid_, clipOpen_);
          },
          withoutPaths)
      .pass(
          ShutterPathPass::kResolveName,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            shutterPath_->recordResolve(frame, *f.scene, visibility_, clipCurrent_, clipMid_, clipOpen_, paths_,
                                        size_.width(), size_.height());
          },
          withoutPaths);
}

void GBufferStage::plan(FramePlan& plan, const GpuScene& scene) const { passes_.plan(plan, {&scene}); }

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
  passes_.recordAll(frame, {&scene});
}

}  // namespace hmb::passes
