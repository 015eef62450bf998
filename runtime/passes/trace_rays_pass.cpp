#include "runtime/passes/trace_rays_pass.h"

#include "kernels/trace/trace_layout.h"
#include "runtime/error.h"
#include "runtime/trace_scene.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

TraceRaysPass::TraceRaysPass(const vk::Context& context)
    : kernel_(context, "trace/trace_rays", sizeof(gpu::TraceParams)) {}

void TraceRaysPass::record(vk::FrameRecorder& frame, const TraceScene& scene, const vk::Buffer& rays,
                           const vk::Buffer& hits, uint32_t rayCount, uint32_t flags) const {
  if (scene.timeCount() == 0) throw Error("trace-rays: the scene's shutter times are not set");
  const gpu::TraceParams params{rayCount, scene.instanceCount(), scene.timeCount(), flags};
  vk::Bindings bindings = {{HMB_TRACE_BINDING_RAYS, &rays}, {HMB_TRACE_BINDING_HITS, &hits}};
  scene.bind(bindings, HMB_TRACE_BINDING_SCENE, kernel_.bindsByAddress());
  frame.dispatch(kName, kernel_, bindings, params,
                 vk::foldedGroups(vk::groupsFor(rayCount, HMB_TRACE_GROUP)));
}

}  // namespace hmb::passes
