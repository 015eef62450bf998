#include "runtime/passes/trace_rays_pass.h"

#include "kernels/trace/trace_layout.h"
#include "runtime/error.h"
#include "runtime/trace_scene.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

TraceRaysPass::TraceRaysPass(const vk::Context& context)
    : kernel_(context, "trace/trace_rays", HMB_TRACE_BINDING_COUNT, sizeof(gpu::TraceParams)) {}

void TraceRaysPass::record(vk::FrameRecorder& frame, const TraceScene& scene, const vk::Buffer& rays,
                           const vk::Buffer& hits, uint32_t rayCount, uint32_t flags) const {
  if (scene.timeCount() == 0) throw Error("trace-rays: the scene's shutter times are not set");
  const gpu::TraceParams params{rayCount, scene.instanceCount(), scene.timeCount(), flags};
  frame.dispatch(kName, kernel_, {&rays, &hits, &scene.table()}, params,
                 vk::foldedGroups(vk::groupsFor(rayCount, HMB_TRACE_GROUP)));
}

}  // namespace hmb::passes
