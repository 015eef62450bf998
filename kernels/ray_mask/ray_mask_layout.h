// Layout of the ray mask's kernels (kernels/ray_mask/), the paper's section 3.2, steps 1 and 2:
// the pixels whose blur may cross another object's edge, for the reveal (kernels/reveal/).
//   tile_max_edge_candidates    the gather's tile-max, and eqs. 1, 2 at each pixel it reads:
//                  moving pixels whose predicted end position lies on a different, deeper
//                  object, listed (a few percent of the pixels); and the moving tiles, listed
//   edge_mask      eqs. 3, 4: the listed candidates whose 5x5 Sobel of depth and normal passes
//                  the edge threshold e (listing first keeps the Sobel's lanes busy)
//   list_range_blocks  the 8 x 8 blocks of the moving tiles with a flagged coarse edge block
//                  within their tile's fastest reach, listed: no pixel of another block can meet
//                  an edge
//   range_check    pixels of the listed blocks whose range along their velocity meets the edge
//                  mask: the ray mask, per pixel HMB_MASK_* (for the gathers), and a compacted
//                  list of the pixels to reveal (with the coverage composite: marked only)
//   list_range_mask       with the coverage composite, the marked pixels listed block by block
//                  for mask_coverage (which splits them between the reveal and the composite
//                  alone, and list_mask_blocks lists them so)
//   size_list_dispatch    a list's length -> the indirect dispatch of the passes over it, so
//                  an empty list dispatches nothing (the shutter rays' lists too)
// Shared by the GLSL kernels and the C++ passes and reference.
#ifndef HMB_KERNELS_RAY_MASK_RAY_MASK_LAYOUT_H
#define HMB_KERNELS_RAY_MASK_RAY_MASK_LAYOUT_H

#include "../mblur/mblur_hash.h"
#include "../mblur/mblur_layout.h"
#include "../shared/dispatch.h"
#include "../shared/glsl_cpp.h"
#include "../shared/layer_layout.h"

// range_check: one invocation per pixel of the listed blocks, an 8 x 8 group per block: one
// block a group on a GPU, which wants many groups in flight; on a CPU device about
// HMB_RANGE_CHECK_CPU_GROUPS groups in all, enough to keep every thread busy without paying
// llvmpipe 22.3's cost per group (bistro at 1280x720 has 14,400 blocks in its moving tiles),
// each taking a run of consecutive entries: the mask's list then keeps the blocks' order,
// which the reveal's rays and the background gather's reads were 20% faster for on bistro than
// with the list's entries dealt out in turn. A run is at most HMB_RANGE_CHECK_MAX_RUN blocks,
// and fewer where the driver has a loop budget its walks could pass (SizeListParams::loopBudget:
// llvmpipe 22.3 ends every loop of an invocation past 65535 rounds in all, silently): a pixel's
// walks take at most 4 s + 16 rounds for a walk speed s (SizeListParams::walkSpeed), so a run is
// at most loopBudget / (4 s + 17) blocks.
// list_range_blocks: a lane per 8 x 8 block of the moving tiles (a 64-lane group per tile
// left most lanes of its vectors idle at the default tiles, 25 blocks of 40 px, and gave a
// lane a quarter of a 1024-px tile's blocks, past the loop budget).
#define HMB_MASK_TILE_GROUP_X 8
#define HMB_MASK_TILE_GROUP_Y 8
#define HMB_RANGE_CHECK_CPU_GROUPS 256u
#define HMB_RANGE_CHECK_MAX_RUN 16384u


// tile_max_edge_candidates: one HMB_TILE_MAX_GROUP_X x HMB_TILE_MAX_GROUP_Y group per tile, as
// the gather's tile_max.
// uvec4 per pixel: the G-buffer's surfaces (object id, depth: shared/layer_layout.h)
#define HMB_TILE_MAX_CANDIDATES_BINDING_SURFACES 0
#define HMB_TILE_MAX_CANDIDATES_BINDING_TILE_MAX 1  // vec4 per tile: written as tile_max writes it
#define HMB_TILE_MAX_CANDIDATES_BINDING_COUNTERS 2  // RayMaskCounters: candidateCount, tileCount
#define HMB_TILE_MAX_CANDIDATES_BINDING_LIST 3      // uint pixel index per candidate, in no order
// uint tile index per moving tile (as list_moving_tiles lists them), in no order
#define HMB_TILE_MAX_CANDIDATES_BINDING_MOVING_TILES 4
// vec2 per pixel: the G-buffer's velocities (shared/layer_layout.h), as tile_max reads them
#define HMB_TILE_MAX_CANDIDATES_BINDING_VELOCITIES 5
#define HMB_TILE_MAX_CANDIDATES_BINDING_COUNT 6

#define HMB_EDGE_MASK_BINDING_SURFACES 0      // uvec4 per pixel: the G-buffer's surfaces (normal, depth)
#define HMB_EDGE_MASK_BINDING_COUNTERS 1      // RayMaskCounters: candidateCount
#define HMB_EDGE_MASK_BINDING_CANDIDATES 2    // tile_max_edge_candidates' list
// The edge mask (a bit a pixel: edgeMaskBit), then the coarse edge mask (HMB_EDGE_BLOCKS_FIRST):
// set in the mask, 0 elsewhere (written where set only; the buffer is filled with 0 before).
#define HMB_EDGE_MASK_BINDING_EDGES 3
#define HMB_EDGE_MASK_BINDING_COUNT 4

// Side of the blocks of the coarse edge image, in pixels. A block is flagged when an edge
// pixel lies within one pixel of it, so a segment passing through no flagged block passes
// farther than a pixel from every edge pixel (range_check's early out).
#define HMB_EDGE_BLOCK 4u
// Blocks across a side of n pixels (the coarse image is row-major, this many per row).
#define HMB_EDGE_BLOCKS_ACROSS(n) (((n) + HMB_EDGE_BLOCK - 1u) / HMB_EDGE_BLOCK)
// The edge buffer of a width x height image: a bit per pixel, 32 to a uint (the edge mask:
// edgeMaskBit); then the coarse mask twice from HMB_EDGE_BLOCKS_FIRST on: a uint per
// HMB_EDGE_BLOCK^2 block (HMB_EDGE_BLOCK_ENTRY: the range check's walks step from block to
// block by adding 1 or a row), then a bit per block, each row of blocks starting a word
// (HMB_EDGE_BLOCK_WORD: list_range_blocks reads a window of up to 16 blocks across in one or
// two words a row, where it read each block's uint, which took longer:
// bench/results/packed-masks/); this many entries in all.
#define HMB_EDGE_MASK_WORDS(pixels) (((pixels) + 31u) / 32u)
#define HMB_EDGE_BLOCKS_FIRST(width, height) HMB_EDGE_MASK_WORDS((width) * (height))
#define HMB_EDGE_BLOCK_BITS_FIRST(width, height) \
  (HMB_EDGE_BLOCKS_FIRST(width, height) + HMB_EDGE_BLOCKS_ACROSS(width) * HMB_EDGE_BLOCKS_ACROSS(height))
#define HMB_EDGE_ROW_WORDS(width) ((HMB_EDGE_BLOCKS_ACROSS(width) + 31u) / 32u)
#define HMB_EDGE_BUFFER_ENTRIES(width, height) \
  (HMB_EDGE_BLOCK_BITS_FIRST(width, height) + HMB_EDGE_ROW_WORDS(width) * HMB_EDGE_BLOCKS_ACROSS(height))
// The edge buffer's entry of coarse block (x, y).
#define HMB_EDGE_BLOCK_ENTRY(width, height, x, y) \
  (HMB_EDGE_BLOCKS_FIRST(width, height) + (y) * HMB_EDGE_BLOCKS_ACROSS(width) + (x))
// The edge buffer's word holding coarse block (x, y)'s bit, bit x % 32.
#define HMB_EDGE_BLOCK_WORD(width, height, x, y) \
  (HMB_EDGE_BLOCK_BITS_FIRST(width, height) + (y) * HMB_EDGE_ROW_WORDS(width) + (x) / 32u)

#define HMB_RANGE_BLOCKS_GROUP 64
#define HMB_RANGE_BLOCKS_BINDING_TILES 0     // uint tile index per moving tile
#define HMB_RANGE_BLOCKS_BINDING_TILE_MAX 1  // vec4 per tile: the gather's tile-max (velocity, speed)
#define HMB_RANGE_BLOCKS_BINDING_EDGES 2     // the edge mask, then the coarse one (edge_mask)
#define HMB_RANGE_BLOCKS_BINDING_COUNTERS 3  // RayMaskCounters: rangeBlockCount
#define HMB_RANGE_BLOCKS_BINDING_LIST 4      // uint per listed block (rangeBlockEntry below), in no order
#define HMB_RANGE_BLOCKS_BINDING_COUNT 5
// A block's reach is tested over at most this many coarse blocks a side; a wider one is listed
// untested (its walks cost less than the test would, and (16 + 1)^2 rounds keep a lane well
// within the loop budget).
#define HMB_RANGE_BLOCKS_MAX_TEST_SIDE 16

#define HMB_RANGE_CHECK_BINDING_SURFACES 0  // uvec4 per pixel: the G-buffer's surfaces
#define HMB_RANGE_CHECK_BINDING_EDGES 1     // the edge mask, then the coarse one (edge_mask)
#define HMB_RANGE_CHECK_BINDING_BLOCKS 2    // list_range_blocks' list
// The ray mask (2 bits a pixel: HMB_MASK_*, 0 outside it): each mask pixel set to
// HMB_MASK_REVEALED, or with HMB_RANGE_CHECK_LIST_UNCOVERED to HMB_MASK_UNREVEALED until
// mask_coverage tests it (list_range_mask lists them for it).
#define HMB_RANGE_CHECK_BINDING_MASK 3
#define HMB_RANGE_CHECK_BINDING_COUNTERS 4  // RayMaskCounters
// uint pixel index per mask pixel, in no order, from the front (maskCount); unwritten with
// HMB_RANGE_CHECK_LIST_UNCOVERED.
#define HMB_RANGE_CHECK_BINDING_LIST 5
#define HMB_RANGE_CHECK_BINDING_SHUTTER_PATHS 6  // uvec2 per pixel (gbuffer/gbuffer_layout.h), read along curved paths
#define HMB_RANGE_CHECK_BINDING_COUNT 7

// Ray mask values: a mask pixel is revealed (listed for the reveal, its revealed surface then
// written) or not (the coverage composite gives its background no weight).
#define HMB_MASK_NONE 0u
#define HMB_MASK_UNREVEALED 1u
#define HMB_MASK_REVEALED 2u
// The ray mask buffer holds each pixel's value in 2 bits (mblur_layout.h: rayMaskValue).

// RayMaskParams.flags: list only the mask pixels whose coverage composite samples (the
// gather's, same positions and jitter) meet the background; the others blend it with weight
// exactly 0, so their reveal would change nothing. The range check marks every mask pixel
// (HMB_MASK_UNREVEALED), list_range_mask lists them for mask_coverage, which tests them: in a
// list, the pixels a CPU device's lanes test are the mask's alone, where inside the range check
// each vector with one mask pixel ran the samples for all its lanes (bistro at 1280x720: 40,067
// mask pixels among 0.9 million walked).
#define HMB_RANGE_CHECK_LIST_UNCOVERED 1u

// list_range_mask: with HMB_RANGE_CHECK_LIST_UNCOVERED, a lane per block the range check walked
// (its list's order): the block's mask pixels, in row order, appended to mask_coverage's list
// with one atomic. The range check appended each mask pixel itself before: one counter's
// atomic per pixel from every thread of a CPU device (a good part of its time:
// bench/results/range-mask-list/), and the list in whatever order the threads met them.
#define HMB_RANGE_MASK_LIST_GROUP 64
#define HMB_RANGE_MASK_LIST_BINDING_BLOCKS 0    // list_range_blocks' list (rangeBlockCount)
#define HMB_RANGE_MASK_LIST_BINDING_MASK 1      // the ray mask, as the range check marked it
#define HMB_RANGE_MASK_LIST_BINDING_COUNTERS 2  // RayMaskCounters: coverageCount grows
#define HMB_RANGE_MASK_LIST_BINDING_LIST 3      // uint pixel index per mask pixel, for mask_coverage
#define HMB_RANGE_MASK_LIST_BINDING_COUNT 4

// mask_coverage: the coverage composite's share of each mask pixel (paper, section 3; see
// composite.comp), HMB_MASK_LIST_GROUP pixels a group, over the range check's mask pixels as
// list_range_mask lists them: the mean
// colour of the pixel and its samples on its object, and alpha, for the composite; the mask's
// value, and its block's bit, for the reveal where a sample meets the background, for the
// composite alone otherwise (list_mask_blocks lists them).
#define HMB_MASK_COVERAGE_BINDING_SAMPLES 0        // uvec4 per pixel: the G-buffer's samples (colour, depth)
#define HMB_MASK_COVERAGE_BINDING_SURFACES 1       // uvec4 per pixel: the G-buffer's surfaces (velocity, object id)
#define HMB_MASK_COVERAGE_BINDING_SHUTTER_PATHS 2  // uvec2 per pixel (gbuffer/gbuffer_layout.h), read along curved paths
#define HMB_MASK_COVERAGE_BINDING_PIXELS 3         // list_range_mask's list: uint pixel index, coverageCount of them
#define HMB_MASK_COVERAGE_BINDING_COUNTERS 4       // RayMaskCounters
#define HMB_MASK_COVERAGE_BINDING_COVERAGE 5       // vec4 per pixel: (mean colour, alpha), written at mask pixels
// The ray mask: HMB_MASK_UNREVEALED at the listed pixels (the range check's), turned to
// HMB_MASK_REVEALED where a sample meets the background.
#define HMB_MASK_COVERAGE_BINDING_MASK 6
// uvec4 per HMB_MASK_BLOCK^2 block of the image, cleared before: a bit per pixel, (x, y) of the
// block at bit 8 y + x of xy where the pixel needs the reveal, of zw where it does not.
#define HMB_MASK_COVERAGE_BINDING_BLOCK_BITS 7
#define HMB_MASK_COVERAGE_BINDING_COUNT 8
// Read through texel views (counted in kernels/manifest.h): the G-buffer's samples and surfaces, the shutter paths.
#define HMB_SPEC_MASK_COVERAGE_CURVED_PATH 0  // the curved path's code, built only for frames that take it

// list_mask_blocks: with the coverage composite, the mask's list, one lane per 8 x 8 block of
// the image (blocks aligned to the image's corner), in row order of blocks: each block's pixels
// mask_coverage marked as needing the reveal at the list's front, the others at its back, the
// block's together, in row order. mask_coverage's lanes meet in whatever order its threads
// run; in a list that keeps neighbours together the reveal's rays and the background gather's
// reads find what their group's other lanes have just brought into the cache (bistro at
// 1280x720 on a CPU device: the reveal and the background gather each about a quarter faster,
// bench/results/mask-list-order/).
#define HMB_MASK_BLOCK 8u
#define HMB_MASK_BLOCKS_ACROSS(n) (((n) + HMB_MASK_BLOCK - 1u) / HMB_MASK_BLOCK)
#define HMB_LIST_MASK_BLOCKS_GROUP 64
#define HMB_LIST_MASK_BLOCKS_BINDING_BLOCK_BITS 0  // uvec4 per block (mask_coverage), read as texels
#define HMB_LIST_MASK_BLOCKS_BINDING_COUNTERS 1    // RayMaskCounters: maskCount, unrevealedCount grow
#define HMB_LIST_MASK_BLOCKS_BINDING_LIST 2        // the mask's list
#define HMB_LIST_MASK_BLOCKS_BINDING_COUNT 3
// Read through a texel view (counted in kernels/manifest.h): the block bits.

#define HMB_SIZE_LIST_BINDING_COUNTERS 0
#define HMB_SIZE_LIST_BINDING_COUNT 1
// SizeListParams.list
#define HMB_SIZE_LIST_MASK 1u             // HMB_MASK_LIST_GROUP mask pixels per group
// Both lists the hybrid's tile-max makes: the moving tiles (a lane per block of each,
// HMB_RANGE_BLOCKS_GROUP a group; SizeListParams::tileBlocks to a tile) and the edge candidates
// (HMB_MASK_LIST_GROUP a group).
#define HMB_SIZE_LIST_TILES_AND_CANDIDATES 2u
// One group per listed block, or SizeListParams::groupsWanted in all (more where a group's
// run would pass HMB_RANGE_CHECK_MAX_RUN blocks); and a lane per listed block for
// list_range_mask.
#define HMB_SIZE_LIST_RANGE_BLOCKS 3u
#define HMB_SIZE_LIST_COVERAGE 4u  // HMB_MASK_LIST_GROUP of the range check's mask pixels per group
// The moving tiles' 8 x 8 blocks for list_shutter_rays: one group per block, or
// SizeListParams::groupsWanted in all (more where a group's run would pass the loop budget).
#define HMB_SIZE_LIST_SHUTTER_BLOCKS 5u

// The list passes (edge_mask, reveal_background, gather_background) run 64 lanes per group.
#define HMB_MASK_LIST_GROUP 64

// The mask's kernels and list_shutter_rays read the G-buffer's surfaces (and samples, and
// range_check the shutter paths) as uniform texel buffers, even where they use a word or two of
// a record: on lavapipe a storage-buffer load at per-lane addresses is a loop over the lanes
// with a branch each, which was most of the tile-max test's cost and half the shutter rays'
// list's (bench/results/texel-reads/). A single word (the edge mask, the ray mask) reads no
// faster through a texel view. kernels/manifest.h counts each kernel's texel views.
// range_check's curved-path code, compiled in only where the blur takes the curved path
// (HMB_GATHER_FLAG_CURVED_PATH): on a CPU device its walks ran, at least a round of each loop,
// for every pixel of a straight frame.
#define HMB_SPEC_RANGE_CHECK_CURVED_PATH 0
// tile_max_edge_candidates: true, the test inside the reduction's loop; false, after it in the
// tiles with a moving pixel (see the kernel: the host picks by device type and camera motion).
#define HMB_SPEC_TILE_MAX_CANDIDATES_IN_LOOP 0

// RayMaskCounters::dispatches: the indirect dispatch of each pass over a list, sized by
// size_list_dispatch from the list's count.
#define HMB_RAY_MASK_DISPATCH_MASK 0            // the mask list's passes over its front (maskCount)
#define HMB_RAY_MASK_DISPATCH_UNREVEALED 1      // the coverage composite over its back (unrevealedCount)
#define HMB_RAY_MASK_DISPATCH_CANDIDATES 2      // edge_mask over the candidates (candidateCount)
#define HMB_RAY_MASK_DISPATCH_TILE_BLOCKS 3     // list_range_blocks, a lane per block of the moving tiles
#define HMB_RAY_MASK_DISPATCH_RANGE_CHECK 4     // range_check over the listed blocks (rangeBlockCount)
#define HMB_RAY_MASK_DISPATCH_RANGE_LIST 5      // list_range_mask over the same blocks
#define HMB_RAY_MASK_DISPATCH_COVERAGE 6        // mask_coverage over coverageCount pixels
#define HMB_RAY_MASK_DISPATCH_SHUTTER_BLOCKS 7  // list_shutter_rays over the moving tiles' blocks
#define HMB_RAY_MASK_DISPATCHES 8

HMB_GPU_BEGIN

// Cleared each frame. maskCount (the list's front: the pixels listed for the reveal) and
// unrevealedCount (its back: the other mask pixels): range_check; maskPixels (their sum) and
// the dispatches: size_list_dispatch; rayCount: reveal_background; tileCount:
// list_moving_tiles or tile_max_edge_candidates; candidateCount: tile_max_edge_candidates;
// rangeBlockCount: list_range_blocks; coverageCount: list_range_mask.
struct RayMaskCounters {
  uint maskCount;
  uint unrevealedCount;
  uint maskPixels;  // every pixel of the ray mask: maskCount + unrevealedCount
  uint rayCount;    // closest-hit traces the reveal made
  uint tileCount;
  uint candidateCount;
  uint rangeBlockCount;  // 8 x 8 blocks listed for the range check
  uint coverageCount;    // mask pixels the range check listed for mask_coverage
  IndirectDispatch dispatches[HMB_RAY_MASK_DISPATCHES];  // [HMB_RAY_MASK_DISPATCH_*]
};

struct SizeListParams {
  uint list;  // HMB_SIZE_LIST_*
  // range blocks, shutter blocks: the groups wanted in all, each taking a run of the blocks (0:
  // one per block)
  uint groupsWanted;
  // range blocks, shutter blocks: the farthest a pixel's walk may reach, in pixels. The range
  // check's: the largest speed (GatherParams::maxSpeed), twice that along curved paths
  // (|v| + 2 |q|); the shutter list's: the larger of the largest speed and the tile size (a
  // still pixel walks its tile's fastest, clamped to the tile)
  float walkSpeed;
  uint tileBlocks;  // tiles and candidates, shutter blocks: the 8 x 8 blocks of a tile (tileBlocks() below)
  // range blocks, shutter blocks: the loop rounds an invocation may take (vk::DeviceProfile::
  // loopBudget), which a run of blocks stays within; 0: the driver has no budget
  uint loopBudget;
};

// tile_max_edge_candidates, edge_mask and range_check: the blur's own parameters this frame (its tiles,
// velocity scale, maximum speed, SOFT_Z_EXTENT, samples and seed), so that the mask finds the
// pixels the gathers will blur as they blur them; then the mask's own.
struct RayMaskParams {
  GatherParams blur;
  float edgeThreshold;  // e: eq. 4's x_n must exceed it
  uint flags;           // HMB_RANGE_CHECK_*
  uint pad0;
  uint pad1;
};

// A block list_range_blocks lists for range_check: its first pixel x | y << 14 (image sides are
// at most 2^14: include/hmblur/renderer.h), and whether it is its tile's last block across and down,
// which a tile side that is no multiple of 8 cuts short. The range check finds its pixels with
// no division (a CPU device divides lane by lane).
#define HMB_RANGE_BLOCK_LAST_ACROSS (1u << 28u)
#define HMB_RANGE_BLOCK_LAST_DOWN (1u << 29u)
HMB_SHARED uint rangeBlockEntry(uvec2 origin, bool lastAcross, bool lastDown) {
  return origin.x | (origin.y << 14u) | (lastAcross ? HMB_RANGE_BLOCK_LAST_ACROSS : 0u) |
         (lastDown ? HMB_RANGE_BLOCK_LAST_DOWN : 0u);
}
HMB_SHARED uvec2 rangeBlockOrigin(uint entry) { return uvec2(entry & 0x3FFFu, (entry >> 14u) & 0x3FFFu); }

// Whether pixel `pixel`'s bit is set in its word of the edge mask (word pixel / 32).
HMB_SHARED bool edgeMaskBit(uint word, uint pixel) { return ((word >> (pixel % 32u)) & 1u) != 0u; }

// How many 8 x 8 blocks a tile has across, down and in all.
HMB_SHARED uint tileBlocksAcross(uint tileSize) {
  return (tileSize + HMB_MASK_TILE_GROUP_X - 1u) / HMB_MASK_TILE_GROUP_X;
}
HMB_SHARED uint tileBlocksDown(uint tileSize) {
  return (tileSize + HMB_MASK_TILE_GROUP_Y - 1u) / HMB_MASK_TILE_GROUP_Y;
}
HMB_SHARED uint tileBlocks(uint tileSize) { return tileBlocksAcross(tileSize) * tileBlocksDown(tileSize); }

HMB_GPU_END

HMB_CHECK_SIZE(RayMaskCounters, 128)

#ifdef __cplusplus
#include <cstddef>

namespace hmb::gpu {
// Where dispatch `dispatch` (HMB_RAY_MASK_DISPATCH_*) lies in the counters buffer, for
// vkCmdDispatchIndirect.
inline constexpr uint64_t rayMaskDispatchOffset(uint32_t dispatch) {
  return offsetof(RayMaskCounters, dispatches) + dispatch * sizeof(IndirectDispatch);
}
}  // namespace hmb::gpu
#endif
HMB_CHECK_SIZE(SizeListParams, 20)
HMB_CHECK_SIZE(RayMaskParams, 80)

#endif
