#include "runtime/passes/resolve_gbuffer_pass.h"

#include <span>
#include <string>
#include <vector>

#include "hmblur/error.h"
#include "kernels/gbuffer/gbuffer_layout.h"
#include "kernels/manifest.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

ResolveGBufferPass::ResolveGBufferPass(const vk::Context& context)
    : kernel_(context, kernels::kernel("gbuffer/resolve_gbuffer")) {}

void ResolveGBufferPass::record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& visibility,
                                const vk::Buffer& clipCurrent, const vk::Buffer& clipPrevious,
                                const vk::Buffer& vertexShading, const ImageLayer& target, uint32_t width,
                                uint32_t height) const {
  // The kernel reads the visibility entries as whole 16-byte records.
  RasterizePass::requireVisibilityBuffer(visibility, width, height, kName);
  // Empty pixels lie at the far plane, so depth comparisons treat them as the farthest surface.
  const gpu::ResolveParams params{width, height, scene.camera().zfar, 0};
  const vk::ComputeKernel& kernel = kernel_.forScene(scene);
  vk::Bindings bindings = {{HMB_RESOLVE_BINDING_VISIBILITY, &visibility},
                           {HMB_RESOLVE_BINDING_TRIANGLES, &scene.triangles()},
                           {HMB_RESOLVE_BINDING_CLIP_CURRENT, &clipCurrent},
                           {HMB_RESOLVE_BINDING_CLIP_PREVIOUS, &clipPrevious},
                           {HMB_RESOLVE_BINDING_SHADING, &vertexShading}};
  scene.bind(bindings, HMB_RESOLVE_BINDING_SCENE, kernel.bindsByAddress());
  target.bind(bindings, HMB_RESOLVE_BINDING_GBUFFER, kernel.bindsByAddress());
  if (!target.velocities().handle()) throw Error(std::string(kName) + ": the G-buffer keeps no velocities");
  bindings.push_back({HMB_RESOLVE_BINDING_VELOCITIES, &target.velocities()});
  frame.dispatch(kName, kernel, bindings, params,
                 {vk::groupsFor(width, HMB_RESOLVE_GROUP_X), vk::groupsFor(height, HMB_RESOLVE_GROUP_Y), 1});
}

}  // namespace hmb::passes
