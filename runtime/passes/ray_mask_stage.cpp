#include "runtime/passes/ray_mask_stage.h"

#include <string>

#include "kernels/hybrid/hybrid_layout.h"
#include "runtime/error.h"
#include "runtime/frame_plan.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

RayMaskStage::RayMaskStage(const vk::Context& context)
    : context_(context),
      edgeKernel_(context, "hybrid/edge_mask", HMB_EDGE_MASK_BINDING_COUNT, sizeof(gpu::EdgeMaskParams)),
      rangeKernel_(context, "hybrid/range_check", HMB_RANGE_CHECK_BINDING_COUNT, sizeof(gpu::RangeCheckParams)),
      sizeKernel_(context, "hybrid/size_reveal_dispatch", HMB_SIZE_REVEAL_BINDING_COUNT, 0) {}

void RayMaskStage::plan(FramePlan& plan) const {
  plan.run(kClear);
  plan.run(kEdges);
  plan.run(kRangeCheck);
  plan.run(kSizeDispatch);
}

void RayMaskStage::prepare(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) throw Error("ray mask: empty image");
  if (width == width_ && height == height_) return;
  const uint64_t pixels = uint64_t(width) * height;
  edges_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "edge mask");
  mask_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "ray mask");
  list_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "ray mask list");
  counters_ = vk::Buffer(context_, sizeof(gpu::RayMaskCounters), vk::MemoryUse::Device, "ray mask counters");
  width_ = width;
  height_ = height;
}

void RayMaskStage::record(vk::FrameRecorder& frame, const MotionBlurInputs& layer, const vk::Buffer& objectId,
                          const RayMaskParameters& p) const {
  if (layer.width != width_ || layer.height != height_)
    throw Error("ray mask: inputs are " + std::to_string(layer.width) + "x" + std::to_string(layer.height) +
                " but the stage was prepared for " + std::to_string(width_) + "x" + std::to_string(height_));
  const glm::uvec3 groups{vk::groupsFor(width_, HMB_EDGE_MASK_GROUP_X), vk::groupsFor(height_, HMB_EDGE_MASK_GROUP_Y),
                          1};
  frame.fill(kClear, counters_, 0u);
  const gpu::EdgeMaskParams edgeParams{width_, height_, p.velocityScale, p.maxSpeed, p.softZExtent, p.edgeThreshold,
                                       0u, 0u};
  frame.dispatch(kEdges, edgeKernel_, {layer.normalDepth, layer.velocity, &objectId, &edges_}, edgeParams, groups);
  const gpu::RangeCheckParams rangeParams{width_, height_, p.velocityScale, p.maxSpeed};
  frame.dispatch(kRangeCheck, rangeKernel_, {layer.velocity, &edges_, &mask_, &counters_, &list_}, rangeParams,
                 glm::uvec3{vk::groupsFor(width_, HMB_RANGE_CHECK_GROUP_X),
                            vk::groupsFor(height_, HMB_RANGE_CHECK_GROUP_Y), 1});
  const vk::Buffer* sizeBuffers[] = {&counters_};
  frame.dispatch(kSizeDispatch, sizeKernel_, sizeBuffers, {}, {1, 1, 1});
}

RayMaskCounts RayMaskStage::counts() const {
  const auto c = counters_.download<gpu::RayMaskCounters>();
  return {c.at(0).maskCount, c.at(0).rayCount};
}

}  // namespace hmb::passes
