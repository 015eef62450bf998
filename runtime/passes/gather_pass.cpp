#include "runtime/passes/gather_pass.h"

#include <algorithm>
#include <cstddef>
#include <string>
#include <span>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

gpu::GatherParams gatherParams(const PostProcessSettings& settings, uint32_t width, uint32_t height,
                               MaskWeights mask) {
  const uint32_t tileSize = settings.effectiveTileSize();
  const TileGrid grid = tileGridFor(width, height, tileSize);
  const uint32_t flags = settings.range == GatherRange::Adapted ? HMB_GATHER_FLAG_ADAPTED_RANGE : 0u;
  return gpu::GatherParams{width,
                           height,
                           tileSize,
                           grid.x,
                           grid.y,
                           settings.samples,
                           settings.seed,
                           flags,
                           gatherVelocityScale(settings.range, settings.exposure, settings.fps),
                           settings.softZExtent,
                           settings.effectiveForegroundBoost(),
                           mask.backgroundBoost,
                           mask.foregroundDivide,
                           float(std::max(width, height)),
                           settings.foregroundBoostPixelsPerSlice(),
                           0};
}

namespace {

// Where a block list's indirect dispatch lies in gpu::GatherBlockCounters.
constexpr VkDeviceSize listDispatchOffset(uint32_t list) {
  return offsetof(gpu::GatherBlockCounters, lists) + list * sizeof(gpu::GatherBlockList) +
         offsetof(gpu::GatherBlockList, dispatchX);
}

}  // namespace

GatherPass::GatherPass(const vk::Context& context)
    : context_(context),
      kernels_(context, kernels::kernel("mblur/gather")),
      listBlocks_(context, kernels::kernel("mblur/list_gather_blocks")),
      copyStillBlocks_(context, kernels::kernel("mblur/copy_still_blocks")) {}

void GatherPass::plan(FramePlan& plan) const {
  plan.run(kClearBlocks);
  plan.run(kListBlocks);
  plan.run(kName);
  plan.run(kCopyStillBlocks);
}

uint32_t GatherPass::recordBlockLists(vk::FrameRecorder& frame, uint32_t width, uint32_t height, uint32_t tileSize,
                                  const vk::Buffer& neighborMax) const {
  const uint32_t blocksX = vk::groupsFor(width, HMB_GATHER_BLOCK), blocksY = vk::groupsFor(height, HMB_GATHER_BLOCK);
  // A list entry holds a block's place in 16 bits an axis.
  if (blocksX > 0xFFFFu || blocksY > 0xFFFFu)
    throw Error("gather: " + std::to_string(width) + "x" + std::to_string(height) + " has more than 65535 blocks of " +
                std::to_string(HMB_GATHER_BLOCK) + " pixels on a side");
  const uint64_t blockCount = uint64_t(blocksX) * blocksY;
  if (blocks_.size() < blockCount * sizeof(uint32_t))
    blocks_ = vk::Buffer(context_, blockCount * sizeof(uint32_t), vk::MemoryUse::Device, "gather blocks");
  if (!blockCounters_.handle())
    blockCounters_ = vk::Buffer(context_, sizeof(gpu::GatherBlockCounters), vk::MemoryUse::Device, "gather block counters");
  frame.fill(kClearBlocks, blockCounters_, 0u);
  const TileGrid grid = tileGridFor(width, height, tileSize);
  const gpu::GatherBlocksParams params{width, height, tileSize, grid.x, blocksX, uint32_t(blockCount), 0, 0};
  frame.dispatch(kListBlocks, listBlocks_,
                 {{HMB_GATHER_BLOCKS_BINDING_NEIGHBOR_MAX, &neighborMax},
                  {HMB_GATHER_BLOCKS_BINDING_COUNTERS, &blockCounters_},
                  {HMB_GATHER_BLOCKS_BINDING_LIST, &blocks_}},
                 params, vk::foldedGroups(vk::groupsFor(uint32_t(blockCount), HMB_GATHER_BLOCKS_GROUP)));
  return uint32_t(blockCount);
}

std::unique_ptr<GatherFilter> makeMcGuireGather(const vk::Context& context) {
  return std::make_unique<GatherPass>(context);
}

void GatherPass::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                        const vk::Buffer& output, const PostProcessSettings& settings) const {
  // The mask is read only by the hybrid's variant; the output stands in.
  recordWith(false, frame, inputs, neighborMax, output, settings, output);
}

void GatherPass::recordOutsideMask(vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                                   const vk::Buffer& neighborMax, const vk::Buffer& output,
                                   const PostProcessSettings& settings, const vk::Buffer& mask) const {
  recordWith(true, frame, inputs, neighborMax, output, settings, mask);
}

void GatherPass::recordWith(bool outsideMask, vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                            const vk::Buffer& neighborMax, const vk::Buffer& output,
                            const PostProcessSettings& settings, const vk::Buffer& mask) const {
  const bool curved = settings.motionPath == MotionPath::Curved;
  if (curved && !inputs.shutterPaths)
    throw Error("post-process: the curved motion path needs the G-buffer's shutter paths");
  // The gather is built for its frame's path and range alone: on lavapipe the code of the
  // others runs for every sample whether or not the flags ask for it.
  const bool adapted = settings.range == GatherRange::Adapted;
  static_assert(HMB_SPEC_GATHER_OUTSIDE_MASK == 0 && HMB_SPEC_GATHER_CURVED_PATH == 1 &&
                HMB_SPEC_GATHER_ADAPTED_RANGE == 2);
  const vk::ComputeKernel& kernel = kernels_.with({outsideMask, curved, adapted});
  gpu::GatherParams params = gatherParams(settings, inputs.width, inputs.height);
  if (curved) params.flags |= HMB_GATHER_FLAG_CURVED_PATH;
  const uint32_t blockCount = recordBlockLists(frame, inputs.width, inputs.height, params.tileSize, neighborMax);
  vk::Bindings bindings = filterBindings(inputs, neighborMax, output);
  bindings.push_back({HMB_GATHER_BINDING_MASK, &mask});
  bindings.push_back({HMB_GATHER_BINDING_BLOCKS, &blocks_});
  bindings.push_back({HMB_GATHER_BINDING_BLOCK_COUNTERS, &blockCounters_});
  frame.dispatchIndirect(kName, kernel, bindings, params, blockCounters_,
                         listDispatchOffset(HMB_GATHER_BLOCKS_MOVING));

  // The same for the hybrid: its mask has no pixel in a still block (copy_still_blocks.comp).
  const gpu::StillBlocksParams still{inputs.width, inputs.height, blockCount, 0};
  frame.dispatchIndirect(kCopyStillBlocks, copyStillBlocks_,
                         {{HMB_STILL_BLOCKS_BINDING_SAMPLES, inputs.samples},
                          {HMB_STILL_BLOCKS_BINDING_OUTPUT, &output},
                          {HMB_STILL_BLOCKS_BINDING_BLOCKS, &blocks_},
                          {HMB_STILL_BLOCKS_BINDING_COUNTERS, &blockCounters_}},
                         still, blockCounters_, listDispatchOffset(HMB_GATHER_BLOCKS_STILL));
}

}  // namespace hmb::passes
