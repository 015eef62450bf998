#include "runtime/passes/transform_vertices_pass.h"

#include "kernels/manifest.h"
#include "kernels/raster/raster_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

namespace {
constexpr uint32_t kRigid[] = {0u}, kDeformed[] = {1u};  // HMB_SPEC_TRANSFORM_DEFORMED
}

TransformVerticesPass::TransformVerticesPass(const vk::Context& context)
    : rigid_(context, kernels::kernel("raster/transform_vertices"), kRigid),
      deformed_(context, kernels::kernel("raster/transform_vertices"), kDeformed) {}

void TransformVerticesPass::record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& clipCurrent,
                                   const vk::Buffer& clipPrevious, const vk::Buffer& shading) const {
  const uint32_t vertexCount = scene.instanceVertexCount();
  frame.dispatch(kName, scene.deforms() ? deformed_ : rigid_,
                 {{HMB_TRANSFORM_BINDING_VERTICES, &scene.vertices()},
                  {HMB_TRANSFORM_BINDING_INSTANCE_VERTICES, &scene.instanceVertices()},
                  {HMB_TRANSFORM_BINDING_INSTANCES, &scene.instances()},
                  {HMB_TRANSFORM_BINDING_CAMERA, &scene.cameraBuffer()},
                  {HMB_TRANSFORM_BINDING_CLIP_CURRENT, &clipCurrent},
                  {HMB_TRANSFORM_BINDING_CLIP_PREVIOUS, &clipPrevious},
                  {HMB_TRANSFORM_BINDING_SHADING, &shading},
                  {HMB_TRANSFORM_BINDING_PREVIOUS_VERTICES, &scene.previousVertices()}},
                 vertexCount, vk::foldedGroups(vk::groupsFor(vertexCount, HMB_RASTER_GROUP)));
}

}  // namespace hmb::passes
