#include "runtime/passes/ray_mask_stage.h"

#include <cstddef>
#include <string>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/manifest.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "runtime/passes/tile_max_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

namespace {
// The mask kernels' push constants: the frame's blur, the edge threshold and the range check's
// flags (the other kernels read no flag).
gpu::RayMaskParams maskParams(const RayMaskParameters& p) {
  return {p.blur, p.edgeThreshold, p.listOnlyUncovered ? HMB_RANGE_CHECK_LIST_UNCOVERED : 0u, 0u, 0u};
}
}  // namespace

std::vector<uint32_t> unpackRayMask(std::span<const uint32_t> words, size_t pixels) {
  if (words.size() < HMB_RAY_MASK_WORDS(uint64_t(pixels))) throw Error("ray mask: fewer words than its pixels need");
  std::vector<uint32_t> values(pixels);
  for (size_t i = 0; i < pixels; ++i) values[i] = gpu::rayMaskValue(words[i / 16], uint32_t(i));
  return values;
}

std::vector<uint32_t> packRayMask(std::span<const uint32_t> values) {
  std::vector<uint32_t> words(HMB_RAY_MASK_WORDS(uint64_t(values.size())), 0u);
  for (size_t i = 0; i < values.size(); ++i) {
    if (values[i] > HMB_MASK_REVEALED) throw Error("ray mask: " + std::to_string(values[i]) + " is no mask value");
    words[i / 16] |= gpu::rayMaskBits(values[i], uint32_t(i));
  }
  return words;
}

std::vector<uint32_t> unpackEdgeMask(std::span<const uint32_t> words, size_t pixels) {
  if (words.size() < HMB_EDGE_MASK_WORDS(uint64_t(pixels))) throw Error("edge mask: fewer words than its pixels need");
  std::vector<uint32_t> values(pixels);
  for (size_t i = 0; i < pixels; ++i) values[i] = gpu::edgeMaskBit(words[i / 32], uint32_t(i)) ? 1u : 0u;
  return values;
}

RayMaskStage::RayMaskStage(const vk::Context& context)
    : context_(context),
      passes_(context),
      tilesKernel_(context, kernels::kernel("shutter_rays/list_moving_tiles")),
      edgeKernel_(context, kernels::kernel("ray_mask/edge_mask")),
      sizeKernel_(context, kernels::kernel("ray_mask/size_list_dispatch")),
      blocksKernel_(context, kernels::kernel("ray_mask/list_range_blocks")),
      coveragePass_(context),
      tileMaxKernels_(context, kernels::kernel("ray_mask/tile_max_edge_candidates")),
      rangeKernels_(context, kernels::kernel("ray_mask/range_check")),
      rangeListKernel_(context, kernels::kernel("ray_mask/list_range_mask")) {
  const auto wholeMaskOnly = [](const Frame& f) { return f.movingTilesOnlyBecause; };
  const auto coverageOnly = [](const Frame& f) {
    return f.movingTilesOnlyBecause.empty() ? f.coverageSkipped : f.movingTilesOnlyBecause;
  };
  passes_
      // The whole mask's tile-max clears its buffers before it lists (recordTileMax()); the moving
      // tiles alone start from cleared counters here.
      .pass(kClear,
            [this](vk::FrameRecorder& frame, const Frame& f) {
              if (f.parameters->movingTilesOnly) frame.fill(kClear, counters_, 0u);
            })
      // From the gather's tile-max: the moving tiles alone (the whole mask's tile-max lists them).
      .pass(
          kMovingTiles,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            const TileGrid grid{f.parameters->blur.tilesX, f.parameters->blur.tilesY};
            const gpu::MovingTilesParams tileParams{grid.count(), 0u, 0u, 0u};
            frame.dispatch(kMovingTiles, tilesKernel_,
                           {{HMB_MOVING_TILES_BINDING_TILE_MAX, f.parameters->tileMax},
                            {HMB_MOVING_TILES_BINDING_COUNTERS, &counters_},
                            {HMB_MOVING_TILES_BINDING_LIST, &tiles_}},
                           tileParams, vk::foldedGroups(vk::groupsFor(grid.count(), HMB_MOVING_TILES_GROUP)));
          },
          [](const Frame& f) {
            return f.movingTilesOnlyBecause.empty() ? std::string(kMovingTilesListedByTileMaxReason)
                                                    : std::string();
          })
      // The whole mask's counters were cleared before its tile-max listed the moving tiles and the
      // candidates.
      .pass(
          kSizeDispatch,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            recordSizeDispatch(frame, f, HMB_SIZE_LIST_TILES_AND_CANDIDATES, 0u);
          },
          wholeMaskOnly)
      .pass(
          kEdges,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            frame.dispatchIndirect(kEdges, edgeKernel_,
                                   {{HMB_EDGE_MASK_BINDING_SURFACES, f.layer->surfaces},
                                    {HMB_EDGE_MASK_BINDING_COUNTERS, &counters_},
                                    {HMB_EDGE_MASK_BINDING_CANDIDATES, &candidates_},
                                    {HMB_EDGE_MASK_BINDING_EDGES, &edges_}},
                                   maskParams(*f.parameters), counters_,
                                   gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_CANDIDATES));
          },
          wholeMaskOnly)
      .pass(
          kRangeBlocks,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            frame.dispatchIndirect(kRangeBlocks, blocksKernel_,
                                   {{HMB_RANGE_BLOCKS_BINDING_TILES, &tiles_},
                                    {HMB_RANGE_BLOCKS_BINDING_TILE_MAX, f.parameters->tileMax},
                                    {HMB_RANGE_BLOCKS_BINDING_EDGES, &edges_},
                                    {HMB_RANGE_BLOCKS_BINDING_COUNTERS, &counters_},
                                    {HMB_RANGE_BLOCKS_BINDING_LIST, &rangeBlocks_}},
                                   maskParams(*f.parameters), counters_,
                                   gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_TILE_BLOCKS));
          },
          wholeMaskOnly)
      // The range check's groups (kernels/ray_mask/ray_mask_layout.h).
      .pass(
          kSizeDispatch,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            recordSizeDispatch(frame, f, HMB_SIZE_LIST_RANGE_BLOCKS,
                               f.parameters->rangeCheckGroups.value_or(context_.profile().rangeCheckGroups));
          },
          wholeMaskOnly)
      .pass(
          kRangeCheck,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            const MotionBlurInputs& layer = *f.layer;
            const gpu::RayMaskParams params = maskParams(*f.parameters);
            // Built with the curved paths' walks only where the frame takes them.
            static_assert(HMB_SPEC_RANGE_CHECK_CURVED_PATH == 0);
            const bool curved = (f.parameters->blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u;
            frame.dispatchIndirect(
                kRangeCheck, rangeKernels_.with({curved}),
                {{HMB_RANGE_CHECK_BINDING_SURFACES, layer.surfaces},
                 {HMB_RANGE_CHECK_BINDING_EDGES, &edges_},
                 {HMB_RANGE_CHECK_BINDING_BLOCKS, &rangeBlocks_},
                 {HMB_RANGE_CHECK_BINDING_MASK, &mask_},
                 {HMB_RANGE_CHECK_BINDING_COUNTERS, &counters_},
                 {HMB_RANGE_CHECK_BINDING_LIST, &list_},
                 // Read only along curved paths; any buffer stands in otherwise.
                 {HMB_RANGE_CHECK_BINDING_SHUTTER_PATHS, layer.shutterPaths ? layer.shutterPaths : layer.samples}},
                params, counters_, gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_RANGE_CHECK));
            if (!f.parameters->listOnlyUncovered) return;
            // The pixels it marked, listed block by block for the coverage test (timed with it).
            frame.dispatchIndirect(kRangeCheck, rangeListKernel_,
                                   {{HMB_RANGE_MASK_LIST_BINDING_BLOCKS, &rangeBlocks_},
                                    {HMB_RANGE_MASK_LIST_BINDING_MASK, &mask_},
                                    {HMB_RANGE_MASK_LIST_BINDING_COUNTERS, &counters_},
                                    {HMB_RANGE_MASK_LIST_BINDING_LIST, &maskPixels_}},
                                   params, counters_, gpu::rayMaskDispatchOffset(HMB_RAY_MASK_DISPATCH_RANGE_LIST));
          },
          wholeMaskOnly)
      .pass(
          kSizeDispatch,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            recordSizeDispatch(frame, f, HMB_SIZE_LIST_COVERAGE, 0u);
          },
          coverageOnly)
      // mask_coverage and the blocks' list after it.
      .group(
          [coverageOnly](FramePlan& plan, const Frame& f) {
            for (const char* pass : {kCoverage, kListBlocks}) plan.runUnless(pass, coverageOnly(f));
          },
          [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
            if (!plan.runs(kCoverage)) return;
            coveragePass_.record(frame, *f.layer, maskPixels_, counters_, coverage_, mask_, blockBits_, list_,
                                 maskParams(*f.parameters));
          })
      .pass(
          kSizeDispatch,
          [this](vk::FrameRecorder& frame, const Frame& f) { recordSizeDispatch(frame, f, HMB_SIZE_LIST_MASK, 0u); },
          wholeMaskOnly);
}

void RayMaskStage::plan(FramePlan& plan, const std::string& movingTilesOnlyBecause,
                        const std::string& coverageSkipped) const {
  passes_.plan(plan, {nullptr, nullptr, movingTilesOnlyBecause, coverageSkipped});
}

void RayMaskStage::prepare(uint32_t width, uint32_t height, bool movingTilesOnly, bool coverage) {
  if (width == 0 || height == 0) throw Error("ray mask: empty image");
  const uint64_t pixels = uint64_t(width) * height;
  const bool resized = size_.changesTo(width, height);
  if (resized) {
    tiles_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "moving tiles");
    counters_ = vk::Buffer(context_, sizeof(gpu::RayMaskCounters), vk::MemoryUse::Device, "ray mask counters");
    size_.madeFor(width, height);
  }
  if (movingTilesOnly) {
    edges_ = {};
    mask_ = {};
    list_ = {};
    candidates_ = {};
    rangeBlocks_ = {};
    maskPixels_ = {};
    coverage_ = {};
    blockBits_ = {};
    return;
  }
  if (!coverage) {
    maskPixels_ = {};
    coverage_ = {};
    blockBits_ = {};
  } else if (resized || !coverage_.handle()) {
    maskPixels_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "range check mask pixels");
    coverage_ = vk::Buffer(context_, pixels * 4 * sizeof(float), vk::MemoryUse::Device, "mask coverage");
    blockBits_ = vk::Buffer(context_, maskBlockBitsBytes(width, height), vk::MemoryUse::Device, "mask block bits");
  }
  if (!resized && mask_.handle()) return;
  // The edge mask, then the coarse edge mask (kernels/ray_mask/ray_mask_layout.h).
  edges_ = vk::Buffer(context_, HMB_EDGE_BUFFER_ENTRIES(uint64_t(width), uint64_t(height)) * sizeof(uint32_t),
                      vk::MemoryUse::Device, "edge mask");
  mask_ = vk::Buffer(context_, HMB_RAY_MASK_WORDS(pixels) * sizeof(uint32_t), vk::MemoryUse::Device, "ray mask");
  list_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "ray mask list");
  candidates_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "edge candidates");
  // At most a block per pixel, whatever the tile size (a 1-pixel tile is a block).
  rangeBlocks_ = vk::Buffer(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "range check blocks");
}

void RayMaskStage::requireFits(const MotionBlurInputs& layer, const RayMaskParameters& p) const {
  size_.requireMadeFor("ray mask", layer.width, layer.height);
  const gpu::GatherParams& blur = p.blur;
  if (blur.width != size_.width() || blur.height != size_.height())
    throw Error("ray mask: the blur's parameters are for another size");
  const TileGrid grid{blur.tilesX, blur.tilesY};
  if (!p.tileMax || blur.tileSize == 0 || grid.count() == 0) throw Error("ray mask: no tile-max to start from");
  if (uint64_t(grid.x) * blur.tileSize < blur.width || uint64_t(grid.y) * blur.tileSize < blur.height)
    throw Error("ray mask: the tile grid does not cover the image");
  if (!p.movingTilesOnly && !mask_.handle()) throw Error("ray mask: prepared for the moving tiles only");
  if (!p.movingTilesOnly && p.listOnlyUncovered && !coverage_.handle())
    throw Error("ray mask: prepared without the coverage test");
}

void RayMaskStage::recordTileMax(vk::FrameRecorder& frame, const MotionBlurInputs& layer,
                                 const RayMaskParameters& p) const {
  requireFits(layer, p);
  if (p.movingTilesOnly) throw Error("ray mask: the moving tiles alone start from the gather's own tile-max");
  // Pixels outside the moving tiles are never written: they stay out of both masks.
  frame.fill(kClear, counters_, 0u);
  frame.fill(kClear, edges_, 0u);
  frame.fill(kClear, mask_, 0u);
  if (blockBits_.handle()) frame.fill(kClear, blockBits_, 0u);
  // One group per tile, as the gather's tile-max.
  static_assert(HMB_SPEC_TILE_MAX_CANDIDATES_IN_LOOP == 0);
  frame.dispatch(TileMaxPass::kName, tileMaxKernels_.with({p.candidatesInTileMaxLoop}),
                 {{HMB_TILE_MAX_CANDIDATES_BINDING_SURFACES, layer.surfaces},
                  {HMB_TILE_MAX_CANDIDATES_BINDING_VELOCITIES, layer.velocities},
                  {HMB_TILE_MAX_CANDIDATES_BINDING_TILE_MAX, p.tileMax},
                  {HMB_TILE_MAX_CANDIDATES_BINDING_COUNTERS, &counters_},
                  {HMB_TILE_MAX_CANDIDATES_BINDING_LIST, &candidates_},
                  {HMB_TILE_MAX_CANDIDATES_BINDING_MOVING_TILES, &tiles_}},
                 maskParams(p), {p.blur.tilesX, p.blur.tilesY, 1});
}

void RayMaskStage::record(vk::FrameRecorder& frame, const MotionBlurInputs& layer,
                          const RayMaskParameters& p) const {
  requireFits(layer, p);
  const Frame f{&layer, &p, p.movingTilesOnly ? "the moving tiles alone" : "",
                p.listOnlyUncovered ? "" : "every mask pixel is listed"};
  passes_.recordAll(frame, f);
}

void RayMaskStage::recordSizeDispatch(vk::FrameRecorder& frame, const Frame& f, uint32_t list,
                                      uint32_t groupsWanted) const {
  const gpu::GatherParams& blur = f.parameters->blur;
  // How far a range check's walk may reach: the largest speed, twice it along curved paths.
  const float walkSpeed = ((blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u ? 2.0f : 1.0f) * blur.maxSpeed;
  frame.dispatch(kSizeDispatch, sizeKernel_, {{HMB_SIZE_LIST_BINDING_COUNTERS, &counters_}},
                 gpu::SizeListParams{list, groupsWanted, walkSpeed, gpu::tileBlocks(blur.tileSize),
                                     context_.profile().loopBudget.value_or(0u)},
                 {1, 1, 1});
}

RayMaskCounts RayMaskStage::counts() const {
  const auto c = counters_.download<gpu::RayMaskCounters>();
  return {c.at(0).candidateCount, c.at(0).rangeBlockCount, c.at(0).maskPixels, c.at(0).maskCount, c.at(0).rayCount};
}

}  // namespace hmb::passes
