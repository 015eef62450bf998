#include "runtime/passes/shutter_path_pass.h"

#include "kernels/gbuffer/gbuffer_layout.h"
#include "kernels/manifest.h"
#include "kernels/raster/raster_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

namespace {
constexpr uint32_t kRigid[] = {0u}, kDeformed[] = {1u};  // HMB_SPEC_SHUTTER_PATH_DEFORMED
}

ShutterPathPass::ShutterPathPass(const vk::Context& context)
    : rigid_(context, kernels::kernel("raster/transform_shutter_path"), kRigid),
      deformed_(context, kernels::kernel("raster/transform_shutter_path"), kDeformed),
      resolve_(context, kernels::kernel("gbuffer/resolve_shutter_path")) {}

void ShutterPathPass::recordTransform(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& clips,
                                      float exposure, float fps, const vk::Buffer& clipMid,
                                      const vk::Buffer& clipOpen) const {
  const uint32_t vertexCount = scene.instanceVertexCount();
  const float openFrames = exposure * fps;
  const gpu::ShutterPathParams params{vertexCount, 0.5f * openFrames, openFrames, 0};
  frame.dispatch(kTransformName, scene.deforms() ? deformed_ : rigid_,
                 {{HMB_SHUTTER_PATH_BINDING_VERTICES, &scene.vertices()},
                  {HMB_SHUTTER_PATH_BINDING_INSTANCE_VERTICES, &scene.instanceVertices()},
                  {HMB_SHUTTER_PATH_BINDING_SHUTTER_CLIP, &clips},
                  {HMB_SHUTTER_PATH_BINDING_PREVIOUS_VERTICES, &scene.previousVertices()},
                  {HMB_SHUTTER_PATH_BINDING_CLIP_MID, &clipMid},
                  {HMB_SHUTTER_PATH_BINDING_CLIP_OPEN, &clipOpen}},
                 params, vk::foldedGroups(vk::groupsFor(vertexCount, HMB_RASTER_GROUP)));
}

void ShutterPathPass::recordResolve(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& visibility,
                                    const vk::Buffer& clipCurrent, const vk::Buffer& clipMid,
                                    const vk::Buffer& clipOpen, const vk::Buffer& paths, uint32_t width,
                                    uint32_t height) const {
  RasterizePass::requireVisibilityBuffer(visibility, width, height, kResolveName);
  const gpu::ResolveParams params{width, height, scene.camera().zfar, 0};
  frame.dispatch(kResolveName, resolve_,
                 {{HMB_SHUTTER_PATH_RESOLVE_BINDING_VISIBILITY, &visibility},
                  {HMB_SHUTTER_PATH_RESOLVE_BINDING_TRIANGLES, &scene.triangles()},
                  {HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_CURRENT, &clipCurrent},
                  {HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_MID, &clipMid},
                  {HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_OPEN, &clipOpen},
                  {HMB_SHUTTER_PATH_RESOLVE_BINDING_PATHS, &paths}},
                 params, {vk::groupsFor(width, HMB_RESOLVE_GROUP_X), vk::groupsFor(height, HMB_RESOLVE_GROUP_Y), 1});
}

}  // namespace hmb::passes
