// The hybrid method's ray mask (paper, section 3.2.1; kernels/ray_mask/): tile_max_edge_candidates
// (the gather's tile-max, and eqs. 1, 2 at each pixel it reads, listed) -> list_moving_tiles
// -> edge_mask (eqs. 3, 4 over that list) -> list_range_blocks (the blocks with an edge within
// reach) -> range_check (the mask as an image of HMB_MASK_* values and a compacted pixel list;
// with the coverage composite the pixels' list alone) -> mask_coverage (with the coverage
// composite: each mask pixel's alpha and foreground, its mask value and list entry), over the
// moving tiles only, with size_list_dispatch turning each list's length into an indirect
// dispatch. Owns those buffers.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "hmblur/buffer.h"
#include "runtime/passes/gather_filter.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/image_size.h"
#include "runtime/passes/mask_coverage_pass.h"
#include "runtime/passes/pass_list.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/kernel_variants.h"

namespace hmb {
class FramePlan;
}

namespace hmb::passes {

struct RayMaskParameters {
  // The gather's tile-max (PostProcessStage::tileMax()): recordTileMax() writes it for the whole
  // mask; for the moving tiles alone the gather's own tile-max has.
  const vk::Buffer* tileMax = nullptr;
  // The frame's gather parameters (gatherParams()): the mask walks the tiles, velocities (scaled
  // and clamped), depths and samples the gathers will.
  gpu::GatherParams blur{};
  float edgeThreshold = 0.9f;
  // List only the mask pixels whose coverage composite samples (the gather's: its sample count
  // and seed) meet the background: the composite gives the others' reveal a weight of 0. Runs
  // mask_coverage, which also keeps each mask pixel's coverage for the composite (coverage()).
  bool listOnlyUncovered = false;
  // List the moving tiles alone (for the shutter rays' list) and leave the mask empty: the
  // frame traces its edges over the shutter instead of revealing them (HybridStage::plan).
  bool movingTilesOnly = false;
  // Where the hybrid's tile-max runs eqs. 1, 2 (kernels/ray_mask/tile_max_edge_candidates.comp):
  // inside its reduction's loop (a GPU, or a frame whose camera moves: every tile moves), or
  // after it in the tiles with a moving pixel alone (a CPU device runs the loop's test at still
  // pixels too). Either lists the same pixels.
  bool candidatesInTileMaxLoop = true;
  // The range check's groups wanted in all (gpu::SizeListParams::groupsWanted: 0 for one
  // per listed 8 x 8 block); unset: the device's type decides (kernels/ray_mask/ray_mask_layout.h).
  std::optional<uint32_t> rangeCheckGroups;
};

// The ray mask's buffer (2 bits a pixel, 16 to a word: gpu::rayMaskValue) read back as a value
// per pixel (HMB_MASK_*), and per-pixel values packed as it holds them; the edge mask's (a bit a
// pixel, 32 to a word) as 1 at edge pixels, 0 elsewhere.
std::vector<uint32_t> unpackRayMask(std::span<const uint32_t> words, size_t pixels);
std::vector<uint32_t> packRayMask(std::span<const uint32_t> values);
std::vector<uint32_t> unpackEdgeMask(std::span<const uint32_t> words, size_t pixels);

struct RayMaskCounts {
  uint64_t edgeCandidates = 0;  // pixels where eqs. 1-2 hold (the Sobel ran there)
  uint64_t rangeBlocks = 0;     // 8 x 8 blocks the range check walked (an edge within reach)
  uint64_t maskPixels = 0;
  uint64_t listedPixels = 0;  // the mask pixels the reveal traced
  uint64_t revealRays = 0;
};

// Why a frame that reveals the ray mask skips the listing of its moving tiles alone.
inline constexpr const char* kMovingTilesListedByTileMaxReason = "the ray mask's tile-max lists the moving tiles";

class RayMaskStage {
 public:
  static constexpr const char* kClear = "ray-mask-clear";
  static constexpr const char* kMovingTiles = "ray-mask-moving-tiles";
  static constexpr const char* kEdges = "ray-mask-edges";
  static constexpr const char* kRangeBlocks = "ray-mask-range-blocks";
  static constexpr const char* kRangeCheck = "ray-mask-range-check";
  static constexpr const char* kSizeDispatch = "ray-mask-size-dispatch";
  static constexpr const char* kCoverage = MaskCoveragePass::kName;
  static constexpr const char* kListBlocks = MaskCoveragePass::kListName;

  explicit RayMaskStage(const vk::Context& context);
  // movingTilesOnlyBecause: empty for the whole mask; else why the mask's own passes are
  // skipped (RayMaskParameters::movingTilesOnly). coverageSkipped: why mask_coverage is
  // (empty: it runs, RayMaskParameters::listOnlyUncovered).
  void plan(FramePlan& plan, const std::string& movingTilesOnlyBecause = {},
            const std::string& coverageSkipped = {}) const;
  // Sizes the buffers for this resolution (reuses them when it is unchanged); movingTilesOnly:
  // only those of the moving tiles' list (RayMaskParameters::movingTilesOnly), the others freed;
  // coverage: those mask_coverage needs too (RayMaskParameters::listOnlyUncovered).
  void prepare(uint32_t width, uint32_t height, bool movingTilesOnly = false, bool coverage = false);
  // The whole mask's first pass, recorded as the gather's tile-max (TileMaxPass::kName): clears
  // the mask, writes the tile-max into parameters.tileMax as the gather's would, and lists the
  // edge candidates (eqs. 1, 2) in the group that just read the tile
  // (RayMaskParameters::candidatesInTileMaxLoop says where). Neighbour-max and record() follow.
  // Not for the moving tiles alone.
  void recordTileMax(vk::FrameRecorder& frame, const MotionBlurInputs& layer,
                     const RayMaskParameters& parameters) const;
  // layer: the G-buffer (its samples' depths, its surfaces' velocities and ids). After the tile
  // passes: recordTileMax()'s for the whole mask, the gather's own for the moving tiles alone.
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& layer,
              const RayMaskParameters& parameters) const;

  // The mask's own buffers: none after a prepare() for the moving tiles only.
  // A bit per pixel (unpackEdgeMask), then a uint per coarse block.
  const vk::Buffer& edges() const { return edges_; }
  const vk::Buffer& mask() const { return mask_; }  // HMB_MASK_* in 2 bits per pixel (unpackRayMask)
  const vk::Buffer& list() const { return list_; }          // uint pixel index per pixel to reveal
  const vk::Buffer& candidates() const { return candidates_; }  // uint pixel index per edge candidate
  const vk::Buffer& rangeBlocks() const { return rangeBlocks_; }  // gpu::rangeBlockEntry per walked block
  const vk::Buffer& movingTiles() const { return tiles_; }  // uint tile index per moving tile (counters' tileCount)
  const vk::Buffer& counters() const { return counters_; }  // gpu::RayMaskCounters
  // With listOnlyUncovered: the mask's pixels for the coverage test (uint pixel index each,
  // counters' coverageCount), each walked block's together in row order.
  const vk::Buffer& coverageList() const { return maskPixels_; }
  // vec4 per pixel, (foreground colour, alpha) at mask pixels: written with listOnlyUncovered.
  const vk::Buffer& coverage() const { return coverage_; }
  // After the frame: the mask's size and the reveal's traces.
  RayMaskCounts counts() const;

 private:
  // What the mask's passes read this frame, and why the frame leaves some out.
  struct Frame {
    const MotionBlurInputs* layer = nullptr;
    const RayMaskParameters* parameters = nullptr;
    std::string movingTilesOnlyBecause;  // empty: the whole mask
    std::string coverageSkipped;         // empty: mask_coverage runs
  };

  // Throws hmb::Error unless `parameters` fit the prepared size and tile grid.
  void requireFits(const MotionBlurInputs& layer, const RayMaskParameters& parameters) const;
  // A list's length -> the indirect dispatch of the next pass over it (size_list_dispatch).
  void recordSizeDispatch(vk::FrameRecorder& frame, const Frame& f, uint32_t list, uint32_t groupsWanted) const;

  const vk::Context& context_;
  PassList<Frame> passes_;  // record()'s, in frame order

  vk::ComputeKernel tilesKernel_, edgeKernel_, sizeKernel_, blocksKernel_;
  MaskCoveragePass coveragePass_;
  // tile_max_edge_candidates by where its test runs; range_check by path: the straight build
  // has none of the curved walks' code.
  vk::KernelVariants tileMaxKernels_, rangeKernels_;
  vk::ComputeKernel rangeListKernel_;  // list_range_mask: the range check's marks, for the coverage test
  ImageSize size_;
  vk::Buffer edges_, mask_, list_, counters_;
  vk::Buffer candidates_;  // edge candidates: uint pixel index each
  vk::Buffer tiles_;       // moving tiles: at most one per pixel, whatever the tile size
  vk::Buffer rangeBlocks_;  // the range check's 8 x 8 blocks: gpu::rangeBlockEntry each
  // With mask_coverage: the range check's mask pixels (uint pixel index each), and their coverage.
  vk::Buffer maskPixels_, coverage_;
  vk::Buffer blockBits_;  // mask_coverage's bits per 8 x 8 block (HMB_MASK_COVERAGE_BINDING_BLOCK_BITS)
};

}  // namespace hmb::passes
