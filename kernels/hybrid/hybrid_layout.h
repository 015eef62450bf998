// Layout of the hybrid method's kernels (kernels/hybrid/), the paper's section 3.2:
//   tile_max_edge_candidates    the gather's tile-max, and eqs. 1, 2 at each pixel it reads:
//                  moving pixels whose predicted end position lies on a different, deeper
//                  object, listed (a few percent of the pixels); and the moving tiles, listed
//   list_moving_tiles     tiles of the gather's tile-max whose fastest pixel moves half a
//                  pixel or more, for the shutter rays' list (the whole mask's tile-max lists
//                  them itself): only there can a pixel's displacement end on another pixel,
//                  so the mask passes run on those tiles alone (a still scene costs two fills)
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
//                  an empty list dispatches nothing
//   reveal_background     per listed pixel, the first surface behind the object the raster sees
//                  there: its colour, depth, normal, velocity and object id
//   gather_background     the background layer (the raster, the revealed surfaces where
//                  revealed) blurred at the listed pixels; with the coverage composite,
//                  blended under the mask's foreground there
//   composite      the raster layer's gather with the blurred background composited in at
//                  mask pixels (weights), or the mask's foreground at those not revealed
//                  (coverage)
//   list_shutter_rays     pixels of the moving tiles whose path over the shutter crosses
//                  another object or a colour step, listed with the rays each takes (a power of
//                  two): there the single frame the gathers read holds no sub-pixel edge
//                  positions, and a few rays do
//   trace_shutter_rays    per listed pixel, camera rays at that many shutter times, each
//                  through the scene at its own time; their mean replaces the composite's colour
// Shared by the GLSL kernels and the C++ passes and reference.
#ifndef HMB_KERNELS_HYBRID_HYBRID_LAYOUT_H
#define HMB_KERNELS_HYBRID_HYBRID_LAYOUT_H

#include "../shared/dispatch.h"
#include "../shared/glsl_cpp.h"
#include "../mblur/mblur_hash.h"
#include "../mblur/mblur_layout.h"
#include "../shared/layer_layout.h"
#include "../shared/scene_layout.h"
#include "../trace/trace_layout.h"

// list_moving_tiles: one invocation per tile; beside the shutter rays alone (the whole mask's
// tile-max lists the moving tiles as it writes them).
#define HMB_MOVING_TILES_GROUP 64
#define HMB_MOVING_TILES_BINDING_TILE_MAX 0  // vec4 per tile (kernels/mblur/mblur_layout.h), z the speed
#define HMB_MOVING_TILES_BINDING_COUNTERS 1  // RayMaskCounters
#define HMB_MOVING_TILES_BINDING_LIST 2      // uint tile index per moving tile, in no order
#define HMB_MOVING_TILES_BINDING_COUNT 3

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
// lane a quarter of a 1024-px tile's blocks, past the loop budget). list_shutter_rays: an 8 x 8 group per block of the moving tiles, a pixel a lane, on a
// GPU; on a CPU device HMB_SHUTTER_LIST_CPU_GROUPS groups, each a run of consecutive blocks as
// the range check's, at most loopBudget / (s + 6) blocks for a walk speed s (a block's
// pixels take at most s + 3 rounds, a tile 2 more). A group per tile, its lanes striding over
// it, passed the budget with tiles of 128 px and walks of 300 (a lane's last pixels unlisted).
#define HMB_MASK_TILE_GROUP_X 8
#define HMB_MASK_TILE_GROUP_Y 8
#define HMB_RANGE_CHECK_CPU_GROUPS 256u
#define HMB_RANGE_CHECK_MAX_RUN 16384u
#define HMB_SHUTTER_LIST_CPU_GROUPS 256u

// tile_max_edge_candidates: one HMB_TILE_MAX_GROUP_X x HMB_TILE_MAX_GROUP_Y group per tile, as
// the gather's tile_max.
// uvec4 per pixel: the G-buffer's surfaces (velocity, object id, depth: shared/layer_layout.h)
#define HMB_TILE_MAX_CANDIDATES_BINDING_SURFACES 0
#define HMB_TILE_MAX_CANDIDATES_BINDING_TILE_MAX 1  // vec4 per tile: written as tile_max writes it
#define HMB_TILE_MAX_CANDIDATES_BINDING_COUNTERS 2  // RayMaskCounters: candidateCount, tileCount
#define HMB_TILE_MAX_CANDIDATES_BINDING_LIST 3      // uint pixel index per candidate, in no order
// uint tile index per moving tile (as list_moving_tiles lists them), in no order
#define HMB_TILE_MAX_CANDIDATES_BINDING_MOVING_TILES 4
#define HMB_TILE_MAX_CANDIDATES_BINDING_COUNT 5

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
#define HMB_MASK_COVERAGE_TEXEL_BUFFERS 3  // the G-buffer's samples and surfaces, the shutter paths
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
#define HMB_LIST_MASK_BLOCKS_TEXEL_BUFFERS 1  // the block bits

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

// reveal_background
#define HMB_REVEAL_BINDING_CAMERA_RAYS 0  // PinholeCamera at the frame time
#define HMB_REVEAL_BINDING_LIST 1         // the ray mask's pixel list
#define HMB_REVEAL_BINDING_COUNTERS 2     // RayMaskCounters: the list's length; rays are counted into it
// The G-buffer (shared/layer_bindings.glsl, read as texels): its object ids and depths.
#define HMB_REVEAL_BINDING_RASTER 3
// The trace scene (trace/trace_scene_bindings.glsl), the scene's shading buffers
// (shared/scene_bindings.glsl), then the revealed layer, written at the listed pixels
// (shared/layer_bindings.glsl; object id 0 where nothing is behind).
#define HMB_REVEAL_BINDING_TRACE_SCENE (HMB_REVEAL_BINDING_RASTER + HMB_LAYER_BINDINGS)
#define HMB_REVEAL_BINDING_SCENE (HMB_REVEAL_BINDING_TRACE_SCENE + HMB_TRACE_SCENE_BINDINGS)
#define HMB_REVEAL_BINDING_REVEALED (HMB_REVEAL_BINDING_SCENE + HMB_SCENE_BINDINGS)
#define HMB_REVEAL_BINDING_COUNT (HMB_REVEAL_BINDING_REVEALED + HMB_LAYER_BINDINGS)
#define HMB_REVEAL_TEXEL_BUFFERS (HMB_LAYER_BINDINGS + HMB_TRACE_SCENE_TEXEL_BUFFERS + HMB_SCENE_TEXEL_BUFFERS)

// gather_background: the background layer (the raster, the revealed layer where the mask says
// HMB_MASK_REVEALED) blurred at the listed pixels; one invocation per list entry. With the
// coverage composite (HMB_SPEC_BACKGROUND_GATHER_COVERAGE) it also blends the result under
// mask_coverage's foreground and writes the hybrid's image there.
#define HMB_BACKGROUND_GATHER_BINDING_NEIGHBOR_MAX 0  // vec4 per tile
#define HMB_BACKGROUND_GATHER_BINDING_MASK 1          // uint per pixel: HMB_MASK_*
#define HMB_BACKGROUND_GATHER_BINDING_LIST 2          // the ray mask's pixel list
#define HMB_BACKGROUND_GATHER_BINDING_COUNTERS 3      // RayMaskCounters: the list's length
#define HMB_BACKGROUND_GATHER_BINDING_OUTPUT 4        // vec4 per pixel, written at listed pixels
#define HMB_BACKGROUND_GATHER_BINDING_RASTER 5        // the G-buffer (shared/layer_bindings.glsl)
#define HMB_BACKGROUND_GATHER_BINDING_REVEALED (HMB_BACKGROUND_GATHER_BINDING_RASTER + HMB_LAYER_BINDINGS)
// The raster layer's shutter paths (gbuffer/gbuffer_layout.h), read along curved paths.
#define HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS (HMB_BACKGROUND_GATHER_BINDING_REVEALED + HMB_LAYER_BINDINGS)
// vec4 per pixel: mask_coverage's (mean colour, alpha), read with the coverage composite.
#define HMB_BACKGROUND_GATHER_BINDING_COVERAGE (HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS + 1)
#define HMB_BACKGROUND_GATHER_BINDING_COUNT (HMB_BACKGROUND_GATHER_BINDING_COVERAGE + 1)
// Both layers, the paths and the coverage, read as uniform texel buffers.
#define HMB_BACKGROUND_GATHER_TEXEL_BUFFERS 6

// composite: the weights form at every pixel of the ray mask (all at the list's front), one
// invocation per entry; the coverage form at the list's back (the mask pixels not revealed, read
// from the list's end inwards), gather_background having blended its front. The post-process
// gather has written every pixel before.
#define HMB_COMPOSITE_BINDING_NEIGHBOR_MAX 0  // vec4 per tile
#define HMB_COMPOSITE_BINDING_LIST 1          // the ray mask's pixel list
#define HMB_COMPOSITE_BINDING_BACKGROUND 2    // vec4 per pixel: the blurred background (weights form)
#define HMB_COMPOSITE_BINDING_OUTPUT 3        // vec4 per pixel, written at mask pixels
#define HMB_COMPOSITE_BINDING_RASTER 4        // the G-buffer (shared/layer_bindings.glsl)
// The G-buffer's shutter paths (gbuffer/gbuffer_layout.h), read along curved paths.
#define HMB_COMPOSITE_BINDING_SHUTTER_PATHS (HMB_COMPOSITE_BINDING_RASTER + HMB_LAYER_BINDINGS)
#define HMB_COMPOSITE_BINDING_COUNTERS (HMB_COMPOSITE_BINDING_SHUTTER_PATHS + 1)  // RayMaskCounters
// vec4 per pixel: mask_coverage's (mean colour, alpha), read by the coverage form.
#define HMB_COMPOSITE_BINDING_COVERAGE (HMB_COMPOSITE_BINDING_COUNTERS + 1)
#define HMB_COMPOSITE_BINDING_COUNT (HMB_COMPOSITE_BINDING_COVERAGE + 1)
// The G-buffer layer and its paths, the neighbour-max, the background and the coverage: read as
// uniform texel buffers.
#define HMB_COMPOSITE_TEXEL_BUFFERS 6
// The mask's kernels and list_shutter_rays read the G-buffer's surfaces (and samples, and
// range_check the shutter paths) as uniform texel buffers, even where they use a word or two of
// a record: on lavapipe a storage-buffer load at per-lane addresses is a loop over the lanes
// with a branch each, which was most of the tile-max test's cost and half the shutter rays'
// list's (bench/results/texel-reads/). A single word (the edge mask, the ray mask) reads no
// faster through a texel view.
#define HMB_EDGE_MASK_TEXEL_BUFFERS 1
#define HMB_TILE_MAX_CANDIDATES_TEXEL_BUFFERS 1
#define HMB_RANGE_CHECK_TEXEL_BUFFERS 2
// The curved path's code and the range, compiled into the background gather and the composite
// only as the frame takes them (as mblur/gather.comp's): on a CPU device the code of a branch no
// lane takes still runs, and the curved path's reads at every sample cost the background gather
// most of its time (bench/results/hybrid-kernel-shapes/).
#define HMB_SPEC_COMPOSITE_CURVED_PATH 0
#define HMB_SPEC_COMPOSITE_ADAPTED_RANGE 1
#define HMB_SPEC_COMPOSITE_COVERAGE 2  // true: the coverage form (the list's back); false: the weights form
#define HMB_SPEC_BACKGROUND_GATHER_CURVED_PATH 0
#define HMB_SPEC_BACKGROUND_GATHER_ADAPTED_RANGE 1
// true: the coverage composite blended where the background is gathered, at the revealed pixels
// (the composite pass takes the others, a lane's gather code never run for them); false: the
// background alone, for the weights form's composite.
#define HMB_SPEC_BACKGROUND_GATHER_COVERAGE 2
// range_check's curved-path code, compiled in only where the blur takes the curved path
// (HMB_GATHER_FLAG_CURVED_PATH): on a CPU device its walks ran, at least a round of each loop,
// for every pixel of a straight frame.
#define HMB_SPEC_RANGE_CHECK_CURVED_PATH 0
// tile_max_edge_candidates: true, the test inside the reduction's loop; false, after it in the
// tiles with a moving pixel (see the kernel: the host picks by device type and camera motion).
#define HMB_SPEC_TILE_MAX_CANDIDATES_IN_LOOP 0

// list_shutter_rays: an 8 x 8 group per block of the moving tiles, or per run of blocks (above).
#define HMB_SHUTTER_LIST_BINDING_SURFACES 0  // uvec4 per pixel: the G-buffer's surfaces (velocity, object id)
#define HMB_SHUTTER_LIST_BINDING_TILE_MAX 1  // vec4 per tile: the gather's tile-max (velocity, speed)
#define HMB_SHUTTER_LIST_BINDING_TILES 2     // uint tile index per moving tile
#define HMB_SHUTTER_LIST_BINDING_COUNTERS 3  // ShutterRayCounters (cleared each frame)
#define HMB_SHUTTER_LIST_BINDING_LIST 4      // uint per listed pixel: shutterRayEntry(pixel index, rays)
#define HMB_SHUTTER_LIST_BINDING_SAMPLES 5    // uvec4 per pixel: the G-buffer's samples (colour)
#define HMB_SHUTTER_LIST_BINDING_MASK_COUNTERS 6  // RayMaskCounters: the moving tiles' count
#define HMB_SHUTTER_LIST_BINDING_COUNT 7
#define HMB_SHUTTER_LIST_TEXEL_BUFFERS 2  // the surfaces and samples, read as uniform texel buffers

// trace_shutter_rays: one invocation per list entry, HMB_MASK_LIST_GROUP to a group.
#define HMB_SHUTTER_TRACE_BINDING_CAMERAS 0   // PinholeCamera per trace-scene time: the frame's, then each stratum's
#define HMB_SHUTTER_TRACE_BINDING_LIST 1      // list_shutter_rays' list
#define HMB_SHUTTER_TRACE_BINDING_COUNTERS 2  // ShutterRayCounters: the list's length; rays are counted into it
#define HMB_SHUTTER_TRACE_BINDING_OUTPUT 3    // vec4 per pixel: the frame's colour, overwritten at listed pixels
// The trace scene (trace/trace_scene_bindings.glsl), then the scene's shading buffers.
#define HMB_SHUTTER_TRACE_BINDING_TRACE_SCENE 4
#define HMB_SHUTTER_TRACE_BINDING_SCENE (HMB_SHUTTER_TRACE_BINDING_TRACE_SCENE + HMB_TRACE_SCENE_BINDINGS)
#define HMB_SHUTTER_TRACE_BINDING_COUNT (HMB_SHUTTER_TRACE_BINDING_SCENE + HMB_SCENE_BINDINGS)

// A listed pixel takes a ray per this many pixels of the fastest blur around it (at least 2,
// at most the strata): 1 px gained little over 2 px for many more rays, 4 px lost a little for a
// few fewer (bench/results/hybrid-kernel-shapes/).
#define HMB_SHUTTER_RAY_SPACING 2.0f
// A colour step along a path that lists the pixel too (an edge of a texture or of shading on
// one object sweeps over it as an object's edge does): a change of more than this in a channel
// of shutterRayColorKey. Smaller steps list more rays and gain more; this one sits between
// (bench/results/hybrid-kernel-shapes/).
#define HMB_SHUTTER_RAY_COLOR_STEP 0.1f
// The most shutter strata (and so rays per pixel) a frame can have.
#define HMB_MAX_SHUTTER_STRATA 16u
// A list entry: the pixel index in the low 28 bits, log2 of its rays in the high 4 (images are
// at most 16384 x 16384 pixels, 2^28: hmb::kMaxImageSide).
#define HMB_SHUTTER_ENTRY_PIXEL_BITS 28u

// reveal_background's stop, a specialization constant (the build has only its own mode's code:
// on a CPU device the luminance mode's traces and shading ran, without a lane, for every ray of
// the object-id mode, a good part of the reveal: bench/results/hybrid-kernel-shapes/)
#define HMB_SPEC_REVEAL_STOP HMB_SPEC_KERNEL_CONSTANTS_FIRST
#define HMB_REVEAL_STOP_OBJECT_ID 0u  // the first surface of another object (one trace, the object skipped whole)
#define HMB_REVEAL_STOP_LUMINANCE 1u  // the paper's mode: step past hits until the luminance differs

HMB_GPU_BEGIN

// Cleared each frame. maskCount (the list's front: the pixels listed for the reveal) and
// unrevealedCount (its back: the other mask pixels): range_check; maskPixels (their sum) and
// the *Dispatch triples (VkDispatchIndirectCommands): size_list_dispatch; rayCount:
// reveal_background; tileCount: list_moving_tiles or tile_max_edge_candidates; candidateCount:
// tile_max_edge_candidates; rangeBlockCount: list_range_blocks.
struct RayMaskCounters {
  uint maskCount;
  uint maskDispatchX;  // the mask list's passes
  uint maskDispatchY;
  uint maskDispatchZ;
  uint rayCount;  // closest-hit traces the reveal made
  uint tileCount;
  uint rangeDispatchX;  // range_check over the listed blocks
  uint rangeDispatchY;
  uint rangeDispatchZ;
  uint maskPixels;  // every pixel of the ray mask: maskCount + unrevealedCount
  uint candidateCount;
  uint candidateDispatchX;  // edge_mask over the candidates
  uint candidateDispatchY;
  uint candidateDispatchZ;
  uint tileBlockDispatchX;  // a lane per block of the moving tiles (list_range_blocks)
  uint tileBlockDispatchY;
  uint tileBlockDispatchZ;
  uint unrevealedCount;     // mask pixels whose composite needs no reveal, listed from the list's back
  uint unrevealedDispatchX;  // the coverage composite over the list's back (unrevealedCount)
  uint unrevealedDispatchY;
  uint unrevealedDispatchZ;
  uint rangeBlockCount;  // 8 x 8 blocks listed for the range check
  uint coverageCount;    // mask pixels the range check listed for mask_coverage
  uint coverageDispatchX;  // mask_coverage over them
  uint coverageDispatchY;
  uint coverageDispatchZ;
  uint shutterBlockDispatchX;  // list_shutter_rays over the moving tiles' blocks
  uint shutterBlockDispatchY;
  uint shutterBlockDispatchZ;
  uint rangeListDispatchX;  // list_range_mask over the listed blocks (rangeBlockCount)
  uint rangeListDispatchY;
  uint rangeListDispatchZ;
};

struct MovingTilesParams {
  uint tileCount;
  uint pad0;
  uint pad1;
  uint pad2;
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

struct RevealParams {
  uint width;
  uint height;
  uint instanceCount;
  uint pad0;
  uint maxRecursion;         // luminance mode: hits stepped past at most (>= 1)
  float luminanceThreshold;  // luminance mode: relative difference that ends the recursion
  float tMin;                // the near plane's depth
  float tMax;                // the far plane's depth
  float backgroundDepth;     // depth written where nothing is behind (the G-buffer's far value)
  uint timeCount;            // the trace scene's times; the reveal traces the first, the frame's
  uint pad1;
  uint pad2;
};

// Cleared each frame. count: list_shutter_rays' entries; the dispatch (a
// VkDispatchIndirectCommand) grows with the list, HMB_SHUTTER_RAY_GROUPS_PER_ROW groups to a row;
// rayCount: the rays trace_shutter_rays traced.
struct ShutterRayCounters {
  uint count;
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
  uint rayCount;
  uint pad0;
  uint pad1;
  uint pad2;
};

struct ShutterRayListParams {
  GatherParams blur;  // the frame's blur: its velocities are read as the gathers read them
  uint strata;        // shutter strata of the frame (a power of two, at least 2)
  uint pad0;
  uint pad1;
  uint pad2;
};

struct ShutterRayTraceParams {
  uint width;
  uint height;
  uint instanceCount;
  uint timeCount;  // the trace scene's times: the frame's (index 0), then the strata's (1 + s)
  uint strata;
  float tMin;  // the near plane's depth
  float tMax;  // the far plane's depth
  uint pad0;
};

// A block list_range_blocks lists for range_check: its first pixel x | y << 14 (image sides are
// at most 2^14: runtime/renderer.h), and whether it is its tile's last block across and down,
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

HMB_SHARED uint shutterRayEntry(uint pixelIndex, uint rays) {
  const uint log2Rays = rays >= 16u ? 4u : (rays >= 8u ? 3u : (rays >= 4u ? 2u : 1u));  // rays: 2, 4, 8 or 16
  return pixelIndex | (log2Rays << HMB_SHUTTER_ENTRY_PIXEL_BITS);
}
HMB_SHARED uint shutterRayEntryPixel(uint entry) { return entry & ((1u << HMB_SHUTTER_ENTRY_PIXEL_BITS) - 1u); }
HMB_SHARED uint shutterRayEntryRays(uint entry) { return 1u << (entry >> HMB_SHUTTER_ENTRY_PIXEL_BITS); }

// A colour as the colour-step test compares it: clamped to the display's range and square-rooted,
// near the display's own encoding, so a step means about as much in dark and light colours.
HMB_SHARED vec3 shutterRayColorKey(vec3 linear) { return sqrt(clamp(linear, vec3(0.0f), vec3(1.0f))); }
HMB_SHARED bool shutterRayColorsDiffer(vec3 keyA, vec3 keyB) {
  const vec3 d = abs(keyA - keyB);
  return max(d.x, max(d.y, d.z)) > HMB_SHUTTER_RAY_COLOR_STEP;
}

// The rays of a listed pixel whose neighbourhood blurs at most `fastestSpeed` pixels: one per
// HMB_SHUTTER_RAY_SPACING pixels, rounded up to a power of two, from 2 to the frame's strata.
HMB_SHARED uint shutterRaysFor(float fastestSpeed, uint strata) {
  uint rays = 2u;
  if (fastestSpeed > 2.0f * HMB_SHUTTER_RAY_SPACING) rays = 4u;
  if (fastestSpeed > 4.0f * HMB_SHUTTER_RAY_SPACING) rays = 8u;
  if (fastestSpeed > 8.0f * HMB_SHUTTER_RAY_SPACING) rays = 16u;
  return min(rays, strata);
}

// A pixel's rays take every (strata / rays)-th stratum from this one on: neighbours start at
// different strata, so their few times do not line up into copies of an edge.
HMB_SHARED uint shutterRayFirstStratum(uint pixelIndex, uint rays, uint strata) {
  return mblurHash(pixelIndex, 0x5u, 0x9Bu) % (strata / rays);
}

HMB_GPU_END

#define HMB_SHUTTER_RAY_GROUPS_PER_ROW 65535u

HMB_CHECK_SIZE(ShutterRayCounters, 32)
HMB_CHECK_SIZE(ShutterRayListParams, 80)
HMB_CHECK_SIZE(ShutterRayTraceParams, 32)
HMB_CHECK_SIZE(RayMaskCounters, 128)
HMB_CHECK_SIZE(MovingTilesParams, 16)
HMB_CHECK_SIZE(SizeListParams, 20)
HMB_CHECK_SIZE(RayMaskParams, 80)
HMB_CHECK_SIZE(RevealParams, 48)

#endif
