#include "runtime/passes/transform_vertices_pass.h"

#include "kernels/raster/raster_layout.h"
#include "runtime/gpu_scene.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

TransformVerticesPass::TransformVerticesPass(const vk::Context& context)
    : kernel_(context, "raster/transform_vertices", sizeof(uint32_t)) {}

void TransformVerticesPass::record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& clipCurrent,
                                   const vk::Buffer& clipPrevious, const vk::Buffer& shading) const {
  const uint32_t vertexCount = scene.instanceVertexCount();
  frame.dispatch(kName, kernel_,
                 {{HMB_TRANSFORM_BINDING_VERTICES, &scene.vertices()},
                  {HMB_TRANSFORM_BINDING_INSTANCE_VERTICES, &scene.instanceVertices()},
                  {HMB_TRANSFORM_BINDING_INSTANCES, &scene.instances()},
                  {HMB_TRANSFORM_BINDING_CAMERA, &scene.cameraBuffer()},
                  {HMB_TRANSFORM_BINDING_CLIP_CURRENT, &clipCurrent},
                  {HMB_TRANSFORM_BINDING_CLIP_PREVIOUS, &clipPrevious},
                  {HMB_TRANSFORM_BINDING_SHADING, &shading}},
                 vertexCount, vk::foldedGroups(vk::groupsFor(vertexCount, HMB_RASTER_GROUP)));
}

}  // namespace hmb::passes
