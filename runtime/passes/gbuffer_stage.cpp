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
}

void GBufferStage::prepare(const GpuScene& scene, uint32_t width, uint32_t height) {
  const uint32_t vertices = std::max(1u, scene.instanceVertexCount());
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
}

}  // namespace hmb::passes
