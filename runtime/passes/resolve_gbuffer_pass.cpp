#include "runtime/passes/resolve_gbuffer_pass.h"

#include <span>
#include <vector>

#include "kernels/gbuffer/gbuffer_layout.h"
#include "runtime/gpu_scene.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

ResolveGBufferPass::ResolveGBufferPass(const vk::Context& context)
    : kernel_(context, "gbuffer/resolve_gbuffer", sizeof(gpu::ResolveParams)) {}

void ResolveGBufferPass::record(vk::FrameRecorder& frame, const GpuScene& scene, const vk::Buffer& visibility,
                                const vk::Buffer& clipCurrent, const vk::Buffer& clipPrevious,
                                const vk::Buffer& vertexShading, const ImageLayer& target, uint32_t width,
                                uint32_t height) const {
  // Empty pixels lie at the far plane, so depth comparisons treat them as the farthest surface.
  const gpu::ResolveParams params{width, height, scene.camera().zfar, 0};
  const vk::ComputeKernel& kernel = kernel_.forScene(scene);
  std::vector<const vk::Buffer*> bindings = {&visibility, &scene.triangles(), &clipCurrent, &clipPrevious,
                                             &vertexShading};
  scene.appendBindings(bindings, kernel.bindsByAddress());
  target.appendBindings(bindings, kernel.bindsByAddress());
  frame.dispatch(kName, kernel, bindings, std::as_bytes(std::span(&params, 1)),
                 {vk::groupsFor(width, HMB_RESOLVE_GROUP_X), vk::groupsFor(height, HMB_RESOLVE_GROUP_Y), 1});
}

}  // namespace hmb::passes
