#include "runtime/passes/shutter_rays_pass.h"

#include <algorithm>
#include <cstddef>
#include <span>
#include <string>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/post_process_filter.h"
#include "kernels/manifest.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/ray_mask_stage.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

ShutterRaysPass::ShutterRaysPass(const vk::Context& context, const HitShading* hits)
    : context_(context),
      sizeKernel_(context, kernels::kernel("ray_mask/size_list_dispatch")),
      listKernel_(context, kernels::kernel("shutter_rays/list_shutter_rays")),
      selectKernel_(context, kernels::kernel("shutter_rays/select_ray_budget")),
      tallyKernel_(context, kernels::kernel("shutter_rays/tally_budget_ties")),
      keepKernel_(context, kernels::kernel("shutter_rays/keep_budgeted_rays")),
      traceKernel_(context, kernels::kernel("shutter_rays/trace_shutter_rays"), ShadingKernel::Rays::Traced,
                   hits) {}

void ShutterRaysPass::prepare(uint32_t width, uint32_t height, uint32_t rayBudget) {
  if (width == 0 || height == 0) throw Error("shutter rays: empty image");
  const bool resized = size_.changesTo(width, height);
  const uint64_t listBytes = uint64_t(width) * height * sizeof(uint32_t);
  if (resized) {
    list_ = {};  // the old list goes first: the two never take memory at once
    list_ = vk::Buffer(context_, listBytes, vk::MemoryUse::Device, "shutter ray list");
  }
  if (!counters_.handle())
    counters_ = vk::Buffer(context_, sizeof(gpu::ShutterRayCounters), vk::MemoryUse::Device, "shutter ray counters");
  budget_ = rayBudget;
  if (budget_ == 0) {
    priorities_ = {};
    kept_ = {};
  } else if (resized || !kept_.handle()) {
    priorities_ = {};
    kept_ = {};
    priorities_ = vk::Buffer(context_, listBytes, vk::MemoryUse::Device, "shutter ray priorities");
    kept_ = vk::Buffer(context_, listBytes, vk::MemoryUse::Device, "shutter rays kept by the budget");
  }
  if (budget_ != 0 && !budgetState_.handle()) {
    budgetState_ = vk::Buffer(context_, sizeof(gpu::ShutterRayBudget), vk::MemoryUse::Device, "shutter ray budget");
    keptCounters_ = vk::Buffer(context_, sizeof(gpu::ShutterRayCounters), vk::MemoryUse::Device, "shutter rays kept");
  }
  size_.madeFor(width, height);
}

namespace {

void requireStrata(uint32_t strata) {
  if (strata < 2 || strata > HMB_MAX_SHUTTER_STRATA || (strata & (strata - 1)) != 0)
    throw Error("shutter rays: the strata must be a power of two from 2 to " + std::to_string(HMB_MAX_SHUTTER_STRATA));
}

}  // namespace

void ShutterRaysPass::recordList(vk::FrameRecorder& frame, const MotionBlurInputs& raster,
                                 const gpu::GatherParams& blur, const vk::Buffer& tileMax, const RayMaskStage& rayMask,
                                 uint32_t strata, std::optional<uint32_t> groupsWanted) const {
  size_.requireMadeFor("shutter rays", raster.width, raster.height);
  requireStrata(strata);
  if (blur.width != raster.width || blur.height != raster.height)
    throw Error("shutter rays: the blur's parameters are for another size");
  if (blur.tileSize == 0) throw Error("shutter rays: the blur's tile size is 0");
  frame.fill(kList, counters_, 0u);
  const bool ranks = budget_ != 0;
  if (ranks) {
    // Cleared but for the budget itself, in pairs of rays (every pixel takes an even number).
    gpu::ShutterRayBudget cleared{};
    cleared.budgetPairs = budget_ / 2u;
    const uint64_t pixels = uint64_t(raster.width) * raster.height;
    cleared.rangePixels = uint32_t((pixels + HMB_RAY_BUDGET_BUCKETS - 1) / HMB_RAY_BUDGET_BUCKETS);
    frame.write(kList, budgetState_, std::span<const gpu::ShutterRayBudget>(&cleared, 1));
  }
  // The moving tiles' 8 x 8 blocks -> the list's groups (kernels/shutter_rays/shutter_rays_layout.h). A pixel walks its own
  // velocity, clamped to maxSpeed, or its tile's fastest, clamped to the tile.
  const float walkSpeed = std::max(blur.maxSpeed, float(blur.tileSize));
  const uint32_t groups = groupsWanted.value_or(context_.profile().shutterListGroups);
  const gpu::SizeListParams sizeParams{HMB_SIZE_LIST_SHUTTER_BLOCKS, groups, walkSpeed, gpu::tileBlocks(blur.tileSize),
                                       context_.profile().loopBudget.value_or(0u)};
  frame.dispatch(kList, sizeKernel_, {{HMB_SIZE_LIST_BINDING_COUNTERS, &rayMask.counters()}}, sizeParams, {1, 1, 1});
  const gpu::ShutterRayListParams listParams{blur, strata, ranks ? 1u : 0u, 0u, 0u};
  frame.dispatchIndirect(kList, listKernel_,
                         {{HMB_SHUTTER_LIST_BINDING_SURFACES, raster.surfaces},
                          {HMB_SHUTTER_LIST_BINDING_TILE_MAX, &tileMax},
                          {HMB_SHUTTER_LIST_BINDING_SAMPLES, raster.samples},
                          {HMB_SHUTTER_LIST_BINDING_TILES, &rayMask.movingTiles()},
                          {HMB_SHUTTER_LIST_BINDING_MASK_COUNTERS, &rayMask.counters()},
                          {HMB_SHUTTER_LIST_BINDING_COUNTERS, &counters_},
                          {HMB_SHUTTER_LIST_BINDING_LIST, &list_},
                          // Without a budget nothing is ranked: the list and the counters stand in
                          // for the buffers it does not write.
                          {HMB_SHUTTER_LIST_BINDING_PRIORITIES, ranks ? &priorities_ : &list_},
                          {HMB_SHUTTER_LIST_BINDING_BUDGET, ranks ? &budgetState_ : &counters_}},
                         listParams, rayMask.counters(),
                         gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_SHUTTER_BLOCKS));
}

void ShutterRaysPass::recordBudget(vk::FrameRecorder& frame) const {
  if (budget_ == 0) throw Error("shutter rays: recordBudget() without a ray budget");
  const std::span<const std::byte> noPushConstants;
  const vk::Bindings state = {{HMB_RAY_BUDGET_SELECT_BINDING_BUDGET, &budgetState_}};
  const vk::Bindings entries = {{HMB_RAY_BUDGET_TALLY_BINDING_LIST, &list_},
                                {HMB_RAY_BUDGET_TALLY_BINDING_PRIORITIES, &priorities_},
                                {HMB_RAY_BUDGET_TALLY_BINDING_COUNTERS, &counters_},
                                {HMB_RAY_BUDGET_TALLY_BINDING_BUDGET, &budgetState_}};
  const VkDeviceSize listDispatch = offsetof(gpu::ShutterRayCounters, dispatchX);
  // The threshold bucket, its ties per range of pixels, and the range where they stop fitting.
  frame.dispatch(kBudget, selectKernel_, state, gpu::RayBudgetSelectParams{0u, 0u, 0u, 0u}, {1, 1, 1});
  frame.dispatchIndirect(kBudget, tallyKernel_, std::span<const vk::Binding>(entries), noPushConstants, counters_,
                         listDispatch);
  frame.dispatch(kBudget, selectKernel_, state, gpu::RayBudgetSelectParams{1u, 0u, 0u, 0u}, {1, 1, 1});
  frame.fill(kBudget, keptCounters_, 0u);
  const vk::Bindings keep = {{HMB_RAY_BUDGET_KEEP_BINDING_LIST, &list_},
                             {HMB_RAY_BUDGET_KEEP_BINDING_PRIORITIES, &priorities_},
                             {HMB_RAY_BUDGET_KEEP_BINDING_COUNTERS, &counters_},
                             {HMB_RAY_BUDGET_KEEP_BINDING_BUDGET, &budgetState_},
                             {HMB_RAY_BUDGET_KEEP_BINDING_KEPT, &kept_},
                             {HMB_RAY_BUDGET_KEEP_BINDING_KEPT_COUNTERS, &keptCounters_}};
  frame.dispatchIndirect(kBudget, keepKernel_, std::span<const vk::Binding>(keep), noPushConstants, counters_,
                         listDispatch);
}

void ShutterRaysPass::recordTrace(vk::FrameRecorder& frame, const TraceScene& ts, const GpuScene& gpuScene,
                                  const vk::Buffer& cameras, uint32_t strata, const vk::Buffer& output) const {
  requireStrata(strata);
  if (ts.timeCount() != strata + 1)
    throw Error("shutter rays: the trace scene must hold the frame time and one time per stratum");
  if (cameras.size() < uint64_t(ts.timeCount()) * sizeof(gpu::PinholeCamera))
    throw Error("shutter rays: a camera per trace-scene time is needed");
  const FrameCamera& camera = gpuScene.camera();
  const gpu::ShutterRayTraceParams traceParams{size_.width(), size_.height(), ts.instanceCount(), ts.timeCount(),
                                               strata,        camera.znear,  camera.zfar,         0u};
  const vk::ComputeKernel& kernel = traceKernel_.forScene(gpuScene, &ts);
  vk::Bindings bindings = {{HMB_SHUTTER_TRACE_BINDING_CAMERAS, &cameras},
                           {HMB_SHUTTER_TRACE_BINDING_LIST, &tracedList()},
                           {HMB_SHUTTER_TRACE_BINDING_COUNTERS, &tracedCounters()},
                           {HMB_SHUTTER_TRACE_BINDING_OUTPUT, &output}};
  ts.bind(bindings, HMB_SHUTTER_TRACE_BINDING_TRACE_SCENE, kernel.bindsByAddress());
  gpuScene.bind(bindings, HMB_SHUTTER_TRACE_BINDING_SCENE, kernel.bindsByAddress());
  frame.dispatchIndirect(kTrace, kernel, bindings, traceParams, tracedCounters(),
                         offsetof(gpu::ShutterRayCounters, dispatchX));
}

ShutterRayCounts ShutterRaysPass::counts() const {
  const gpu::ShutterRayCounters listed = counters_.download<gpu::ShutterRayCounters>().at(0);
  const gpu::ShutterRayCounters traced = budget_ != 0 ? keptCounters_.download<gpu::ShutterRayCounters>().at(0) : listed;
  return {listed.count, traced.count, traced.rayCount};
}

}  // namespace hmb::passes
