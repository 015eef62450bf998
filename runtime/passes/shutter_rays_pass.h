// Host side of kernels/shutter_rays/list_shutter_rays.comp and trace_shutter_rays.comp: the pixels
// whose path over the shutter crosses an edge (another object, a colour step), where a gather
// of one frame misses the edge's sub-pixel sweep, take a few rays at stratified shutter times
// (distributed ray tracing, as the reference does) and their mean replaces the composite's
// colour there. Under a ray budget the listed pixels are ranked by the error each is expected to
// remove per ray, and only the best that fit trace (select_ray_budget, tally_budget_ties,
// keep_budgeted_rays).
#pragma once

#include <cstdint>
#include <optional>

#include "hmblur/buffer.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "runtime/passes/gather_filter.h"
#include "runtime/passes/image_size.h"
#include "runtime/passes/shading_kernel.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb {
class GpuScene;
class TraceScene;
}

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

struct MotionBlurInputs;
class RayMaskStage;

struct ShutterRayCounts {
  uint64_t pixels = 0;        // pixels listed
  uint64_t tracedPixels = 0;  // pixels traced: the listed ones, or under a budget those kept
  uint64_t rays = 0;          // rays traced
};

class ShutterRaysPass {
 public:
  static constexpr const char* kList = "shutter-rays-list";
  static constexpr const char* kBudget = "shutter-rays-budget";
  static constexpr const char* kTrace = "shutter-rays-trace";

  // hits: how hits are shaded (null: the library's shading).
  explicit ShutterRaysPass(const vk::Context& context, const HitShading* hits = nullptr);

  // rayBudget: the rays a frame traces at most (0: every listed pixel's).
  void prepare(uint32_t width, uint32_t height, uint32_t rayBudget = 0);
  // The list, after the ray mask in the same frame (its moving tiles and their dispatch).
  // blur: the frame's gather parameters (the mask's); tileMax: the gather's, at blur.tileSize;
  // strata: a power of two from 2 to HMB_MAX_SHUTTER_STRATA; groupsWanted: the list's groups in
  // all, each a run of the moving tiles' 8 x 8 blocks (0: one per block; unset: the device's type
  // decides, kernels/shutter_rays/shutter_rays_layout.h), more where a run would pass llvmpipe's loop budget.
  void recordList(vk::FrameRecorder& frame, const MotionBlurInputs& raster, const gpu::GatherParams& blur,
                  const vk::Buffer& tileMax, const RayMaskStage& rayMask, uint32_t strata,
                  std::optional<uint32_t> groupsWanted = std::nullopt) const;
  // Under a ray budget, after the list: the pixels whose rays fit, best first.
  void recordBudget(vk::FrameRecorder& frame) const;
  // The rays, after the composite: traceScene holds the frame time, then one time per stratum
  // (the strata's centres); cameras a gpu::PinholeCamera per trace-scene time. output:
  // overwritten at the listed pixels.
  void recordTrace(vk::FrameRecorder& frame, const TraceScene& traceScene, const GpuScene& gpuScene,
                   const vk::Buffer& cameras, uint32_t strata, const vk::Buffer& output) const;

  ShutterRayCounts counts() const;
  // shutterRayEntry per listed pixel, counts().pixels of them.
  const vk::Buffer& list() const { return list_; }
  const vk::Buffer& counters() const { return counters_; }  // gpu::ShutterRayCounters
  // shutterRayEntry per traced pixel, counts().tracedPixels of them: the list, or the kept list.
  const vk::Buffer& tracedList() const { return budget_ != 0 ? kept_ : list_; }
  // Under a budget: each list entry's priority bucket, and the budget's histogram and threshold.
  const vk::Buffer& priorities() const { return priorities_; }
  const vk::Buffer& budgetState() const { return budgetState_; }     // gpu::ShutterRayBudget
  const vk::Buffer& keptCounters() const { return keptCounters_; }  // gpu::ShutterRayCounters of the kept list

 private:
  const vk::Buffer& tracedCounters() const { return budget_ != 0 ? keptCounters_ : counters_; }

  const vk::Context& context_;
  vk::ComputeKernel sizeKernel_, listKernel_, selectKernel_, tallyKernel_, keepKernel_;
  ShadingKernel traceKernel_;
  ImageSize size_;
  uint32_t budget_ = 0;
  vk::Buffer list_;
  vk::Buffer counters_;
  // Made under a budget only.
  vk::Buffer priorities_, budgetState_, kept_, keptCounters_;
};

}  // namespace hmb::passes
