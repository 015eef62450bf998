#include "runtime/passes/reveal_pass.h"

#include <span>
#include <vector>

#include <cstddef>

#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/reveal/reveal_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

namespace {

constexpr const kernels::KernelFacts& kKernel = kernels::kernel("reveal/reveal_background");
constexpr uint32_t kObjectIdStop[] = {HMB_REVEAL_STOP_OBJECT_ID};
constexpr uint32_t kLuminanceStop[] = {HMB_REVEAL_STOP_LUMINANCE};

}  // namespace

RevealPass::RevealPass(const vk::Context& context, const HitShading* hits)
    : context_(context),
      hits_(hits),
      objectIdStop_(context, kKernel, ShadingKernel::Rays::Traced, hits, kObjectIdStop) {}

void RevealPass::record(vk::FrameRecorder& frame, const TraceScene& ts, const GpuScene& gpuScene,
                        const vk::Buffer& cameraRays, const ImageLayer& raster, const vk::Buffer& list,
                        const vk::Buffer& counters, const ImageLayer& output, uint32_t width, uint32_t height,
                        const HybridSettings& settings) const {
  if (ts.timeCount() == 0) throw Error("ray reveal: the trace scene holds no shutter time");
  const FrameCamera& camera = gpuScene.camera();
  const gpu::RevealParams params{width,
                                 height,
                                 ts.instanceCount(),
                                 0u,
                                 settings.maxRecursion,
                                 settings.luminanceThreshold,
                                 camera.znear,
                                 camera.zfar,
                                 camera.zfar,
                                 ts.timeCount(),
                                 0u,
                                 0u};
  const bool luminance = settings.stop == RevealStop::Luminance;
  if (luminance && !luminanceStop_)
    luminanceStop_ =
        std::make_unique<ShadingKernel>(context_, kKernel, ShadingKernel::Rays::Traced, hits_, kLuminanceStop);
  const vk::ComputeKernel& kernel = (luminance ? *luminanceStop_ : objectIdStop_).forScene(gpuScene, &ts);
  vk::Bindings bindings = {{HMB_REVEAL_BINDING_CAMERA_RAYS, &cameraRays},
                           {HMB_REVEAL_BINDING_LIST, &list},
                           {HMB_REVEAL_BINDING_COUNTERS, &counters}};
  raster.bind(bindings, HMB_REVEAL_BINDING_RASTER, kernel.bindsByAddress());
  ts.bind(bindings, HMB_REVEAL_BINDING_TRACE_SCENE, kernel.bindsByAddress());
  gpuScene.bind(bindings, HMB_REVEAL_BINDING_SCENE, kernel.bindsByAddress());
  output.bind(bindings, HMB_REVEAL_BINDING_REVEALED, kernel.bindsByAddress());
  frame.dispatchIndirect(kName, kernel, bindings, params, counters,
                         gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_MASK));
}

}  // namespace hmb::passes
