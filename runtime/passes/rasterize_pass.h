// Host side of the compute rasterizer's visibility passes: clears, setup_triangles,
// clip_triangles (for the triangles setup lists), bin_large_triangles and rasterize_tiles (or
// its 32-bit two-pass fallback, or on CPU devices link_tile_pairs and rasterize_tile_lists),
// with size_dispatch sizing the indirect ones.
// Input: clip-space triangles; output: the visibility buffer (uint64 per pixel, read as uvec2
// (triangle id, depth key), HMB_VIS_EMPTY where nothing is hit).
//
// The setup and pair buffers are sized by estimate. When a frame needs more, the kernels flag
// an overflow and rasterize nothing; growIfOverflowed() then sizes the buffers from the
// counters (which keep counting past capacity) and the caller records the frame again.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "hmblur/buffer.h"
#include "hmblur/raster_scheme.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
class Context;
struct FrameTimings;
}

namespace hmb {
class FramePlan;
}

namespace hmb::passes {

VisibilityScheme defaultVisibilityScheme(const vk::Context& context);

// Clip-space triangles to rasterize: GpuTriangle (v0, v1, v2, instance), GpuInstance (for the
// double-sided flag) and one clip-space vec4 per vertex.
struct RasterInputs {
  const vk::Buffer* triangles = nullptr;
  const vk::Buffer* instances = nullptr;
  const vk::Buffer* clipCurrent = nullptr;
  uint32_t triangleCount = 0;
};


class RasterizePass {
 public:
  static constexpr const char* kClearVisibility = "clear-visibility";
  static constexpr const char* kClearCounters = "clear-raster-counters";
  static constexpr const char* kSetup = "setup-triangles";
  static constexpr const char* kSizeClipDispatch = "size-clip-dispatch";
  static constexpr const char* kClip = "clip-triangles";
  static constexpr const char* kSizeDispatch = "size-dispatch";
  static constexpr const char* kBinLarge = "bin-large-triangles";
  static constexpr const char* kRasterize = "rasterize-tiles";
  static constexpr const char* kRasterizeDepth32 = "rasterize-depth32";
  static constexpr const char* kRasterizeIds32 = "rasterize-ids32";
  static constexpr const char* kClearTileLists = "clear-tile-lists";
  static constexpr const char* kLinkTilePairs = "link-tile-pairs";
  static constexpr const char* kRasterizeTileLists = "rasterize-tile-lists";

  RasterizePass(const vk::Context& context, VisibilityScheme scheme);

  VisibilityScheme scheme() const { return scheme_; }

  // Lists the passes record() dispatches, and the ones the scheme leaves out with the reason.
  void plan(FramePlan& plan) const;

  // Makes room for a frame of this many triangles at this size (keeps larger buffers).
  void reserve(uint32_t triangleCount, uint32_t width, uint32_t height);

  // The bytes a visibility buffer of width x height takes: 8 per pixel, rounded up to whole
  // 16-byte records, since resolve_gbuffer reads it as a texel buffer.
  static uint64_t visibilityBytes(uint32_t width, uint32_t height) {
    return (uint64_t(width) * height * sizeof(uint64_t) + 15) / 16 * 16;
  }
  // Throws hmb::Error, naming `pass`, when `visibility` is smaller than visibilityBytes.
  static void requireVisibilityBuffer(const vk::Buffer& visibility, uint32_t width, uint32_t height,
                                      const std::string& pass);
  // visibility: width * height uint64 (visibilityBytes). Call reserve() first.
  void record(vk::FrameRecorder& frame, const RasterInputs& inputs, const vk::Buffer& visibility, uint32_t width,
              uint32_t height) const;

  // After the frame ran: reads the counters into stats(); when a capacity overflowed, grows
  // the buffers to what the frame needed and returns true (the caller records it again).
  // Throws hmb::Error when the frame needs more than the device can hold in one buffer.
  bool growIfOverflowed();

  const RasterStats& stats() const { return stats_; }
  uint32_t setupCapacity() const { return setupCapacity_; }
  uint32_t pairCapacity() const { return pairCapacity_; }
  // The intermediate buffers, for tests of the setup and binning kernels.
  const vk::Buffer& setupBuffer() const { return setup_; }
  const vk::Buffer& pairBuffer() const { return pairs_; }
  // The tile-lists scheme's list heads (a uint per tile); its pairs' .y hold the next pair.
  const vk::Buffer& tileHeadBuffer() const { return tileHeads_; }

 private:
  void allocate(uint32_t setupCapacity, uint32_t pairCapacity);
  void allocateClipList(uint32_t clipCapacity);

  const vk::Context& context_;
  VisibilityScheme scheme_;
  vk::ComputeKernel setupKernel_;
  vk::ComputeKernel clipKernel_;
  vk::ComputeKernel sizeDispatchKernel_;
  vk::ComputeKernel binLargeKernel_;
  vk::ComputeKernel rasterizeKernel_;
  std::optional<vk::ComputeKernel> linkKernel_;  // the tile-lists scheme only
  uint32_t setupCapacity_ = 0;
  uint32_t pairCapacity_ = 0;
  uint32_t clipCapacity_ = 0;
  vk::Buffer setup_;     // SetupTriangle[setupCapacity]
  vk::Buffer large_;     // uint[setupCapacity]
  vk::Buffer clipList_;  // uint[clipCapacity]
  vk::Buffer pairs_;     // uvec2[pairCapacity]
  vk::Buffer counters_;  // RasterCounters
  vk::Buffer tileHeads_; // uint per screen tile: the first pair of its list (tile-lists scheme)
  uint32_t tileCapacity_ = 0;
  RasterStats stats_;
};

// Records (with `record`, which must include `rasterizer`'s passes) and submits a frame until
// the rasterizer's buffers fit it; returns the timings of the frame that fit. Buffers grow to
// what an overflowing frame needed, so the second try fits; throws hmb::Error after three.
vk::FrameTimings submitUntilRasterFits(vk::FrameRecorder& frame, RasterizePass& rasterizer,
                                       const std::function<void(vk::FrameRecorder&)>& record);

}  // namespace hmb::passes
