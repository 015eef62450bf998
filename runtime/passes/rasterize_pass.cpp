#include "runtime/passes/rasterize_pass.h"

#include <algorithm>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/manifest.h"
#include "kernels/raster/raster_layout.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {
namespace {

const kernels::KernelFacts& rasterizeKernel(VisibilityScheme scheme) {
  switch (scheme) {
    case VisibilityScheme::Int64Atomics: return kernels::kernel("raster/rasterize_tiles");
    case VisibilityScheme::Depth32TwoPass: return kernels::kernel("raster/rasterize_tiles_depth32");
    case VisibilityScheme::TileLists: break;
  }
  return kernels::kernel("raster/rasterize_tile_lists");
}

uint32_t tilesAlong(uint32_t pixels) { return vk::groupsFor(pixels, HMB_RASTER_TILE); }

// Room for `needed` plus a quarter, so a frame that grows a little does not overflow again.
uint64_t withHeadroom(uint64_t needed) { return needed + needed / 4 + 1024; }

// Grown buffers fit the frame that overflowed; a third try guards against counters that
// disagree between two recordings of the same frame.
constexpr int kMaxRecordAttempts = 3;

}  // namespace

const char* visibilitySchemeName(VisibilityScheme scheme) {
  switch (scheme) {
    case VisibilityScheme::Int64Atomics: return "int64-atomics";
    case VisibilityScheme::Depth32TwoPass: return "depth32-two-pass";
    case VisibilityScheme::TileLists: return "tile-lists";
  }
  return "";
}

VisibilityScheme defaultVisibilityScheme(const vk::Context& context) {
  // A CPU runs a tile's 64 pixels as vector code over several tiles at once, so per-pixel
  // atomics (each a locked instruction per lane) are what it can skip; GPUs keep atomics.
  if (context.profile().rasterTileLists) return VisibilityScheme::TileLists;
  return context.info().int64BufferAtomics ? VisibilityScheme::Int64Atomics : VisibilityScheme::Depth32TwoPass;
}

RasterizePass::RasterizePass(const vk::Context& context, VisibilityScheme scheme)
    : context_(context),
      scheme_(scheme),
      setupKernel_(context, kernels::kernel("raster/setup_triangles")),
      clipKernel_(context, kernels::kernel("raster/clip_triangles")),
      sizeDispatchKernel_(context, kernels::kernel("raster/size_dispatch")),
      binLargeKernel_(context, kernels::kernel("raster/bin_large_triangles")),
      rasterizeKernel_(context, rasterizeKernel(scheme)) {
  if (scheme == VisibilityScheme::Int64Atomics && !context.info().int64BufferAtomics)
    throw Error("device '" + context.info().name + "' lacks shaderBufferInt64Atomics; use the depth32-two-pass scheme");
  if (scheme == VisibilityScheme::TileLists)
    linkKernel_.emplace(context, kernels::kernel("raster/link_tile_pairs"));
  counters_ = vk::Buffer(context, sizeof(gpu::RasterCounters), vk::MemoryUse::Device, "raster counters");
}

void RasterizePass::plan(FramePlan& plan) const {
  const std::string scheme = std::string(kVisibilitySchemeReason) + visibilitySchemeName(scheme_) + ": ";
  if (scheme_ == VisibilityScheme::TileLists) {
    plan.skip(kClearVisibility, scheme + "rasterize-tile-lists writes every entry");
    plan.run(kClearTileLists);
  } else {
    plan.run(kClearVisibility);
  }
  plan.run(kClearCounters);
  plan.run(kSetup);
  plan.run(kSizeClipDispatch);
  plan.run(kClip);
  plan.run(kSizeDispatch);
  plan.run(kBinLarge);
  if (scheme_ == VisibilityScheme::Int64Atomics) {
    plan.run(kRasterize);
  } else if (scheme_ == VisibilityScheme::TileLists) {
    plan.skip(kRasterize, scheme + "a CPU device keeps each tile's pixels in registers, no per-pixel atomics");
    plan.run(kLinkTilePairs);
    plan.run(kRasterizeTileLists);
  } else {
    plan.skip(kRasterize, scheme + "device lacks shaderBufferInt64Atomics: 32-bit two-pass visibility instead");
    plan.run(kRasterizeDepth32);
    plan.run(kRasterizeIds32);
  }
}

void RasterizePass::allocate(uint32_t setupCapacity, uint32_t pairCapacity) {
  setup_ = vk::Buffer(context_, uint64_t(setupCapacity) * sizeof(gpu::SetupTriangle), vk::MemoryUse::Device,
                      "raster setup triangles");
  large_ = vk::Buffer(context_, uint64_t(setupCapacity) * sizeof(uint32_t), vk::MemoryUse::Device,
                      "raster large triangles");
  pairs_ = vk::Buffer(context_, uint64_t(pairCapacity) * sizeof(glm::uvec2), vk::MemoryUse::Device,
                      "raster tile pairs");
  setupCapacity_ = setupCapacity;
  pairCapacity_ = pairCapacity;
}

void RasterizePass::allocateClipList(uint32_t clipCapacity) {
  clipList_ = vk::Buffer(context_, uint64_t(clipCapacity) * sizeof(uint32_t), vk::MemoryUse::Device, "raster clip list");
  clipCapacity_ = clipCapacity;
}

void RasterizePass::reserve(uint32_t triangleCount, uint32_t width, uint32_t height) {
  // Most triangles give one setup triangle (near clipping may split one into up to six, culling
  // drops many) touching one to four tiles; the reference scenes' large walls and floors touch
  // each tile 4 to 7 times (living-room 6.6 at 640x360), so a first frame rarely has to grow.
  const uint64_t tiles = uint64_t(tilesAlong(width)) * tilesAlong(height);
  const uint64_t setupWanted = withHeadroom(triangleCount);
  const uint64_t pairsWanted = std::max(8 * tiles, 2 * setupWanted);
  const uint64_t range = context_.info().maxStorageBufferRange;
  const auto setupCapacity = static_cast<uint32_t>(std::min<uint64_t>(setupWanted, range / sizeof(gpu::SetupTriangle)));
  const auto pairCapacity = static_cast<uint32_t>(std::min<uint64_t>(pairsWanted, range / sizeof(glm::uvec2)));
  // Few triangles cross the near plane or the guard band.
  const auto clipCapacity = static_cast<uint32_t>(std::min<uint64_t>(triangleCount / 8 + 1024, range / sizeof(uint32_t)));
  if (clipCapacity > clipCapacity_) allocateClipList(clipCapacity);
  if (setupCapacity > setupCapacity_ || pairCapacity > pairCapacity_)
    allocate(std::max(setupCapacity, setupCapacity_), std::max(pairCapacity, pairCapacity_));
  if (scheme_ == VisibilityScheme::TileLists && tiles > tileCapacity_) {
    tileHeads_ = vk::Buffer(context_, tiles * sizeof(uint32_t), vk::MemoryUse::Device, "raster tile list heads");
    tileCapacity_ = static_cast<uint32_t>(tiles);
  }
}

void RasterizePass::requireVisibilityBuffer(const vk::Buffer& visibility, uint32_t width, uint32_t height,
                                            const std::string& pass) {
  if (visibility.size() < visibilityBytes(width, height))
    throw Error(pass + ": visibility buffer '" + visibility.name() + "' is smaller than " + std::to_string(width) +
                "x" + std::to_string(height) + " entries in whole 16-byte records");
}

void RasterizePass::record(vk::FrameRecorder& frame, const RasterInputs& inputs, const vk::Buffer& visibility,
                           uint32_t width, uint32_t height) const {
  if (!setup_.handle()) throw Error("RasterizePass::record() before reserve()");
  requireVisibilityBuffer(visibility, width, height, kRasterize);
  gpu::RasterParams params{};
  params.width = width;
  params.height = height;
  params.triangleCount = inputs.triangleCount;
  params.setupCapacity = setupCapacity_;
  params.pairCapacity = pairCapacity_;
  params.tilesX = tilesAlong(width);
  params.clipCapacity = clipCapacity_;

  const uint64_t tiles = uint64_t(params.tilesX) * tilesAlong(height);
  if (scheme_ == VisibilityScheme::TileLists) {
    if (tiles > tileCapacity_) throw Error("RasterizePass::record() at a larger size than reserve() was given");
    frame.fill(kClearTileLists, tileHeads_, HMB_TILE_LIST_END);
  } else {
    frame.fill(kClearVisibility, visibility, HMB_VIS_EMPTY);
  }
  frame.fill(kClearCounters, counters_, 0u);
  const vk::Bindings setupBindings = {{HMB_SETUP_BINDING_TRIANGLES, inputs.triangles},
                                      {HMB_SETUP_BINDING_INSTANCES, inputs.instances},
                                      {HMB_SETUP_BINDING_CLIP_CURRENT, inputs.clipCurrent},
                                      {HMB_SETUP_BINDING_SETUP, &setup_},
                                      {HMB_SETUP_BINDING_PAIRS, &pairs_},
                                      {HMB_SETUP_BINDING_COUNTERS, &counters_},
                                      {HMB_SETUP_BINDING_LARGE, &large_},
                                      {HMB_SETUP_BINDING_CLIP_LIST, &clipList_}};
  const vk::Bindings sizeBindings = {{HMB_SIZE_DISPATCH_BINDING_COUNTERS, &counters_}};
  const vk::Bindings rasterizeBindings = {{HMB_RASTERIZE_BINDING_SETUP, &setup_},
                                          {HMB_RASTERIZE_BINDING_PAIRS, &pairs_},
                                          {HMB_RASTERIZE_BINDING_COUNTERS, &counters_},
                                          {HMB_RASTERIZE_BINDING_VISIBILITY, &visibility}};
  frame.dispatch(kSetup, setupKernel_, setupBindings, params,
                 vk::foldedGroups(vk::groupsFor(inputs.triangleCount, HMB_RASTER_GROUP)));
  params.pass = 0;
  frame.dispatch(kSizeClipDispatch, sizeDispatchKernel_, sizeBindings, params, {1, 1, 1});
  frame.dispatchIndirect(kClip, clipKernel_, setupBindings, params, counters_, HMB_RASTER_COUNTERS_CLIP_OFFSET);
  params.pass = 1;
  frame.dispatch(kSizeDispatch, sizeDispatchKernel_, sizeBindings, params, {1, 1, 1});
  frame.dispatchIndirect(kBinLarge, binLargeKernel_,
                         {{HMB_BIN_LARGE_BINDING_SETUP, &setup_},
                          {HMB_BIN_LARGE_BINDING_PAIRS, &pairs_},
                          {HMB_BIN_LARGE_BINDING_COUNTERS, &counters_},
                          {HMB_BIN_LARGE_BINDING_LARGE, &large_}},
                         params, counters_, HMB_RASTER_COUNTERS_BIN_LARGE_OFFSET);
  if (scheme_ == VisibilityScheme::Int64Atomics) {
    frame.dispatchIndirect(kRasterize, rasterizeKernel_, rasterizeBindings, params, counters_,
                           HMB_RASTER_COUNTERS_RASTERIZE_OFFSET);
  } else if (scheme_ == VisibilityScheme::TileLists) {
    frame.dispatchIndirect(kLinkTilePairs, *linkKernel_,
                           {{HMB_LINK_BINDING_PAIRS, &pairs_},
                            {HMB_LINK_BINDING_COUNTERS, &counters_},
                            {HMB_LINK_BINDING_HEADS, &tileHeads_}},
                           params, counters_, HMB_RASTER_COUNTERS_RASTERIZE_OFFSET);
    frame.dispatch(kRasterizeTileLists, rasterizeKernel_,
                   {{HMB_TILE_LISTS_BINDING_SETUP, &setup_},
                    {HMB_TILE_LISTS_BINDING_PAIRS, &pairs_},
                    {HMB_TILE_LISTS_BINDING_HEADS, &tileHeads_},
                    {HMB_TILE_LISTS_BINDING_VISIBILITY, &visibility},
                    {HMB_TILE_LISTS_BINDING_COUNTERS, &counters_}},
                   params, vk::foldedGroups(vk::groupsFor(static_cast<uint32_t>(tiles), HMB_RASTER_GROUP)));
  } else {
    params.pass = 0;
    frame.dispatchIndirect(kRasterizeDepth32, rasterizeKernel_, rasterizeBindings, params, counters_,
                           HMB_RASTER_COUNTERS_RASTERIZE_OFFSET);
    params.pass = 1;
    frame.dispatchIndirect(kRasterizeIds32, rasterizeKernel_, rasterizeBindings, params, counters_,
                           HMB_RASTER_COUNTERS_RASTERIZE_OFFSET);
  }
}

bool RasterizePass::growIfOverflowed() {
  gpu::RasterCounters counters{};
  counters_.read(std::as_writable_bytes(std::span<gpu::RasterCounters>(&counters, 1)));
  stats_.setupTriangles = std::min(counters.setupCount, setupCapacity_);
  stats_.tilePairs = std::min(counters.pairCount, pairCapacity_);
  stats_.largeTriangles = counters.largeCount;
  stats_.clippedTriangles = counters.clipCount;
  if (counters.overflow == 0) return false;
  if (counters.overflow & HMB_RASTER_OVERFLOW_TILE_LIST)
    throw Error(std::string("a screen tile holds 65535 triangles or more, past what the tile-lists rasterizer walks on "
                            "device '") +
                context_.info().name + "' (its loops end there): render with RendererOptions::visibilityScheme " +
                visibilitySchemeName(VisibilityScheme::Int64Atomics));

  // The counters kept counting past capacity, so they hold what the frame needs (unless the
  // pair count passed 2^32, which no single buffer can hold anyway).
  const uint64_t range = context_.info().maxStorageBufferRange;
  const uint64_t maxSetup = range / sizeof(gpu::SetupTriangle);
  const uint64_t maxPairs = range / sizeof(glm::uvec2);
  const uint64_t setupNeeded = counters.setupCount;
  const uint64_t pairsNeeded =
      (counters.overflow & HMB_RASTER_OVERFLOW_PAIRS_WRAPPED) ? (uint64_t(1) << 32) : counters.pairCount;
  const uint64_t maxClip = range / sizeof(uint32_t);
  if (counters.overflow & HMB_RASTER_OVERFLOW_CLIP)
    allocateClipList(static_cast<uint32_t>(std::min(withHeadroom(counters.clipCount), maxClip)));
  if (setupNeeded > maxSetup || pairsNeeded > maxPairs)
    throw Error("the frame needs " + std::to_string(setupNeeded) + " set-up triangles and " +
                std::to_string(pairsNeeded) + " (triangle, tile) pairs; device '" + context_.info().name +
                "' holds at most " + std::to_string(maxSetup) + " and " + std::to_string(maxPairs) +
                " in one buffer: lower the resolution or simplify the scene");
  allocate(static_cast<uint32_t>(std::min(withHeadroom(std::max<uint64_t>(setupNeeded, setupCapacity_)), maxSetup)),
           static_cast<uint32_t>(std::min(withHeadroom(std::max<uint64_t>(pairsNeeded, pairCapacity_)), maxPairs)));
  ++stats_.regrowths;
  return true;
}

vk::FrameTimings submitUntilRasterFits(vk::FrameRecorder& frame, RasterizePass& rasterizer,
                                       const std::function<void(vk::FrameRecorder&)>& record) {
  for (int attempt = 1;; ++attempt) {
    frame.begin();
    record(frame);
    vk::FrameTimings timings = frame.submitAndWait();
    if (!rasterizer.growIfOverflowed()) return timings;
    if (attempt == kMaxRecordAttempts)
      throw Error("rasterizer buffers still overflow after " + std::to_string(attempt) + " attempts");
  }
}

}  // namespace hmb::passes
