#include "runtime/passes/trace_rays_pass.h"

#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

TraceRaysPass::TraceRaysPass(const vk::Context& context) : context_(context) {}

void TraceRaysPass::record(vk::FrameRecorder& frame, const TraceScene& scene, const vk::Buffer& rays,
                           const vk::Buffer& hits, uint32_t rayCount, uint32_t flags, TopLevel topLevel) const {
  if (scene.timeCount() == 0) throw Error("trace-rays: the scene's shutter times are not set");
  const bool walksTopLevel = topLevel == TopLevel::Always || scene.instanceCount() != 1;
  std::unique_ptr<vk::ComputeKernel>& kernel = kernels_[walksTopLevel ? 1 : 0];
  if (!kernel) {
    uint32_t specialization[HMB_SPEC_TRACE_TOP_LEVEL + 1] = {};
    specialization[HMB_SPEC_TRACE_TOP_LEVEL] = walksTopLevel ? 1u : 0u;  // VkBool32
    kernel = std::make_unique<vk::ComputeKernel>(context_, kernels::kernel("trace/trace_rays"),
                                                 specialization);
  }
  const gpu::TraceParams params{rayCount, scene.instanceCount(), scene.timeCount(), flags};
  vk::Bindings bindings = {{HMB_TRACE_BINDING_RAYS, &rays}, {HMB_TRACE_BINDING_HITS, &hits}};
  scene.bind(bindings, HMB_TRACE_BINDING_SCENE, kernel->bindsByAddress());
  frame.dispatch(kName, *kernel, bindings, params, vk::foldedGroups(vk::groupsFor(rayCount, HMB_TRACE_GROUP)));
}

}  // namespace hmb::passes
