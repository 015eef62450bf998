#include "runtime/passes/reveal_pass.h"

#include <span>
#include <vector>

#include <cstddef>

#include "kernels/hybrid/hybrid_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/error.h"
#include "runtime/gpu_scene.h"
#include "runtime/trace_scene.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

RevealPass::RevealPass(const vk::Context& context, const HitShading* hits)
    : kernel_(context, "hybrid/reveal_background", sizeof(gpu::RevealParams), ShadingKernel::Rays::Traced, hits) {}

void RevealPass::record(vk::FrameRecorder& frame, const TraceScene& ts, const GpuScene& gpuScene,
                        const vk::Buffer& cameraRays, const vk::Buffer& rasterSurfaces, const vk::Buffer& list,
                        const vk::Buffer& counters, const ImageLayer& output, uint32_t width, uint32_t height,
                        const HybridSettings& settings) const {
  if (ts.timeCount() == 0) throw Error("ray reveal: the trace scene holds no shutter time");
  const FrameCamera& camera = gpuScene.camera();
  const gpu::RevealParams params{width,
                                 height,
                                 ts.instanceCount(),
                                 settings.stop == RevealStop::Luminance ? HMB_REVEAL_STOP_LUMINANCE
                                                                        : HMB_REVEAL_STOP_OBJECT_ID,
                                 settings.maxRecursion,
                                 settings.luminanceThreshold,
                                 camera.znear,
                                 camera.zfar,
                                 camera.zfar,
                                 ts.timeCount(),
                                 0u,
                                 0u};
  const vk::ComputeKernel& kernel = kernel_.forScene(gpuScene, &ts);
  vk::Bindings bindings = {{HMB_REVEAL_BINDING_CAMERA_RAYS, &cameraRays},
                           {HMB_REVEAL_BINDING_LIST, &list},
                           {HMB_REVEAL_BINDING_RASTER_SURFACES, &rasterSurfaces},
                           {HMB_REVEAL_BINDING_COUNTERS, &counters}};
  ts.bind(bindings, HMB_REVEAL_BINDING_TRACE_SCENE, kernel.bindsByAddress());
  gpuScene.bind(bindings, HMB_REVEAL_BINDING_SCENE, kernel.bindsByAddress());
  output.bind(bindings, HMB_REVEAL_BINDING_REVEALED, kernel.bindsByAddress());
  frame.dispatchIndirect(kName, kernel, bindings, params, counters,
                         offsetof(gpu::RayMaskCounters, maskDispatchX));
}

}  // namespace hmb::passes
