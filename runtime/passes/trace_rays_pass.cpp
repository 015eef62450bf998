#include "runtime/passes/trace_rays_pass.h"

#include <array>

#include <span>
#include <vector>

#include "kernels/trace/trace_layout.h"
#include "runtime/error.h"
#include "runtime/trace_scene.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

namespace {
// Specialization constants by id: HMB_SPEC_TRACE_STACK is 1 (id 0 is not the trace's).
std::array<uint32_t, 2> traceSpecialization(uint32_t stackSize) {
  static_assert(HMB_SPEC_TRACE_STACK == 1);
  if (stackSize == 0) throw Error("trace-rays: the stack must hold at least one pending subtree");
  return {0u, stackSize};
}
}  // namespace

TraceRaysPass::TraceRaysPass(const vk::Context& context, uint32_t stackSize)
    : kernel_(context, "trace/trace_rays", sizeof(gpu::TraceParams), traceSpecialization(stackSize)) {}

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
