// Layout of the post-process motion blur kernels (kernels/mblur/): tile_max -> neighbor_max ->
// gather (McGuire et al. 2012 with the paper's appendix weights) or gather_jimenez (Jimenez 2014).
// Shared by the GLSL kernels and the C++ passes and reference.
//
// Tile buffers hold one vec4 per tile: xy the dominant velocity (pixels per exposure, already
// converted and clamped, see mblur_common.glsl), z its speed min(|v|, tileSize) as the ranking
// key, w unused. Ranking by the stored key, not by a length recomputed from the clamped vector,
// keeps every clamped velocity at exactly tileSize, so ties are real ties and their rule (first
// in row-major order) decides them on every device the same way.
#ifndef HMB_KERNELS_MBLUR_MBLUR_LAYOUT_H
#define HMB_KERNELS_MBLUR_MBLUR_LAYOUT_H

#include "../shared/glsl_cpp.h"

// tile_max: one 8 x 8 group per tile; each lane strides over the tile (at most 128 x 128
// pixels per lane for the largest tile, 1024, well under the 65535 loop iterations lavapipe
// allows an invocation), then one lane reduces the 64 lane results.
#define HMB_TILE_MAX_GROUP_X 8
#define HMB_TILE_MAX_GROUP_Y 8
// vec2 per pixel: the G-buffer's velocities q in pixels per frame (shared/layer_layout.h)
#define HMB_TILE_MAX_BINDING_VELOCITIES 0
#define HMB_TILE_MAX_BINDING_TILES 1  // vec4 per tile (see above)
#define HMB_TILE_MAX_BINDING_COUNT 2
// The velocities are read as a uniform texel buffer (counted in kernels/manifest.h).

// neighbor_max: one invocation per tile.
#define HMB_NEIGHBOR_MAX_GROUP_X 8
#define HMB_NEIGHBOR_MAX_GROUP_Y 8
#define HMB_NEIGHBOR_MAX_BINDING_TILE_MAX 0      // vec4 per tile
#define HMB_NEIGHBOR_MAX_BINDING_NEIGHBOR_MAX 1  // vec4 per tile
#define HMB_NEIGHBOR_MAX_BINDING_COUNT 2

// The gathers (every post-process filter's and the hybrid's): one invocation per pixel.
#define HMB_GATHER_GROUP_X 8
#define HMB_GATHER_GROUP_Y 8
// Every post-process filter's gather (gather, gather_jimenez; filter_bindings.glsl).
#define HMB_FILTER_BINDING_SAMPLES 0       // uvec4 per pixel: the layer's samples (shared/layer_layout.h)
#define HMB_FILTER_BINDING_NEIGHBOR_MAX 1  // vec4 per tile
#define HMB_FILTER_BINDING_OUTPUT 2        // vec4 per pixel
#define HMB_FILTER_BINDING_SHUTTER_PATHS 3 // uvec2 per pixel (gbuffer/gbuffer_layout.h)
#define HMB_FILTER_BINDING_COUNT 4
// Samples, neighbour-max and paths are read as uniform texel buffers (counted in kernels/manifest.h).
// gather.comp beside those: the hybrid's ray mask (2 bits a pixel, 16 to a uint: rayMaskValue
// below, 0 outside), read only with HMB_SPEC_GATHER_OUTSIDE_MASK: the gather then leaves the
// mask's pixels to the hybrid's composite.
#define HMB_GATHER_BINDING_MASK HMB_FILTER_BINDING_COUNT
// The moving blocks (HMB_GATHER_BLOCK_*), the only ones gather.comp blurs: list_gather_blocks'
// list and counters.
#define HMB_GATHER_BINDING_BLOCKS (HMB_GATHER_BINDING_MASK + 1)
#define HMB_GATHER_BINDING_BLOCK_COUNTERS (HMB_GATHER_BINDING_MASK + 2)
#define HMB_GATHER_BINDING_COUNT (HMB_GATHER_BINDING_MASK + 3)
#define HMB_SPEC_GATHER_OUTSIDE_MASK 0
// gather.comp's curved-path code, compiled in only where GatherParams::flags asks for the
// curved path (HMB_GATHER_FLAG_CURVED_PATH); without it that flag is not read.
#define HMB_SPEC_GATHER_CURVED_PATH 1
// gather.comp's range: true for HMB_GATHER_FLAG_ADAPTED_RANGE, which it then does not read.
#define HMB_SPEC_GATHER_ADAPTED_RANGE 2

// The gather's blocks: the 8 x 8 pixels of one group (HMB_GATHER_GROUP_X/Y), row-major over
// the image. A block is still when no pixel of it lies in a tile whose neighbour-max speed is
// kMinBlurPixels or more: the gather would leave every pixel its own colour there, which
// copy_still_blocks writes without the gather's reads of the neighbourhood. On a CPU device
// the gather's code runs for every lane of a group whatever its branches take (a loop at least
// once), so a still pixel costs nearly what a moving one does in one sample; on a GPU still
// groups would retire early, and the lists save their launch and keep moving groups dense.
#define HMB_GATHER_BLOCK 8u
// The block list's groups are dispatched this many to a row of the grid (its y the rows), so
// that a large image's blocks never ask for more than 65535 groups on an axis.
#define HMB_GATHER_BLOCKS_PER_ROW 256u
// The two lists (GatherBlockCounters::lists).
#define HMB_GATHER_BLOCKS_MOVING 0
#define HMB_GATHER_BLOCKS_STILL 1
// list_gather_blocks: one invocation per block.
#define HMB_GATHER_BLOCKS_GROUP 64
#define HMB_GATHER_BLOCKS_BINDING_NEIGHBOR_MAX 0  // vec4 per tile
#define HMB_GATHER_BLOCKS_BINDING_COUNTERS 1      // GatherBlockCounters, zero before the pass
// uint per block: the moving blocks from the front, the still ones from the back, each entry
// the block's place (gatherBlockEntry)
#define HMB_GATHER_BLOCKS_BINDING_LIST 2
#define HMB_GATHER_BLOCKS_BINDING_COUNT 3
// copy_still_blocks: one 8 x 8 group per listed still block.
#define HMB_STILL_BLOCKS_BINDING_SAMPLES 0   // uvec4 per pixel: the layer's samples
#define HMB_STILL_BLOCKS_BINDING_OUTPUT 1    // vec4 per pixel
#define HMB_STILL_BLOCKS_BINDING_BLOCKS 2    // list_gather_blocks' list
#define HMB_STILL_BLOCKS_BINDING_COUNTERS 3  // GatherBlockCounters
#define HMB_STILL_BLOCKS_BINDING_COUNT 4

// GatherParams::flags
#define HMB_GATHER_FLAG_ADAPTED_RANGE 1u  // samples over X + u v_N, u in (0, 1]; else McGuire's t in [-1, 1]
// With the adapted range: a pixel moving at least half its tile's neighbour-max speed samples
// along its own curved path over the shutter where the G-buffer has one
// (gbuffer/resolve_shutter_path.comp); the others keep the straight line along v_N
// (gather_samples.glsl). The hybrid's range check and coverage composite follow every path.
#define HMB_GATHER_FLAG_CURVED_PATH 2u

// Velocities are clamped to the tile size (so the 3x3 neighbourhood sees every pixel that can
// reach a tile) and the largest tile size is bounded so per-lane loops stay short.
#define HMB_MBLUR_MAX_TILE_SIZE 1024u
#define HMB_MBLUR_MAX_SAMPLES 255u
#define HMB_MBLUR_MAX_NEIGHBORHOOD 31u

// Colour channels are clamped to +-this (the largest half float) so sums of weighted samples
// stay finite; non-finite channels read as 0.
#define HMB_MBLUR_MAX_COLOR 65504.0
// Depths read as clamp(depth, 0, this); NaN reads as this (farthest).
#define HMB_MBLUR_MAX_DEPTH 3.0e38

HMB_GPU_BEGIN
// Blur under half a pixel moves no pixel centre: a gather whose neighbourhood moves less
// returns the pixel's own colour, and the ray mask leaves tiles that move less alone.
const float kMinBlurPixels = 0.5f;
// The curved path: a pixel samples along its own path when that path is at least this share of
// its tile's neighbour-max speed; slower pixels, which faster neighbours may cover, keep
// McGuire's straight line along the neighbour-max velocity.
const float kOwnPathShare = 0.5f;

// One of list_gather_blocks' lists: its length, and the indirect dispatch of its blocks
// (HMB_GATHER_BLOCKS_PER_ROW groups to a row). All zero before the pass.
struct GatherBlockList {
  uint count;
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
};

struct GatherBlockCounters {
  GatherBlockList lists[2];  // [HMB_GATHER_BLOCKS_MOVING], [HMB_GATHER_BLOCKS_STILL]
};

// A block's list entry: its place in blocks, 16 bits an axis.
HMB_SHARED uint gatherBlockEntry(uvec2 place) { return (place.y << 16u) | place.x; }
HMB_SHARED uvec2 gatherBlockPlace(uint entry) { return uvec2(entry & 0xFFFFu, entry >> 16u); }

// The hybrid's ray mask buffer (kernels/ray_mask/ray_mask_layout.h: HMB_MASK_*) holds each pixel's
// value in 2 bits, 16 pixels to a uint: pixel `pixel`'s value in its word (word pixel / 16), and
// the bits that set it there (by atomicOr). The mask and the edge mask (a bit a pixel) are
// cleared each frame: as a uint a pixel the two fills stored sixteen and thirty-two times as
// much (bench/results/packed-masks/), and a GPU's walks and samples read a sixteenth and a
// thirty-second as many cache lines.
#define HMB_RAY_MASK_WORDS(pixels) (((pixels) + 15u) / 16u)
HMB_SHARED uint rayMaskValue(uint word, uint pixel) { return (word >> (2u * (pixel % 16u))) & 3u; }
HMB_SHARED uint rayMaskBits(uint value, uint pixel) { return value << (2u * (pixel % 16u)); }

struct GatherBlocksParams {
  uint width;
  uint height;
  uint tileSize;
  uint tilesX;
  uint blocksX;
  uint blockCount;
  uint pad0;
  uint pad1;
};

// copy_still_blocks
struct StillBlocksParams {
  uint width;
  uint height;
  uint blockCount;
  uint pad0;
};

struct TileMaxParams {
  uint width;
  uint height;
  uint tileSize;
  uint tilesX;
  uint tilesY;
  float velocityScale;  // q (pixels per frame) -> gather velocity: E * fps, halved for centred ranges
  uint pad0;
  uint pad1;
};

struct NeighborMaxParams {
  uint tilesX;
  uint tilesY;
  uint neighborhood;  // odd
  uint pad0;
};

// The parameters of every McGuire gather: the post-process gather and the hybrid's background
// gather and composite (kernels/reveal/), which must blur alike.
struct GatherParams {
  uint width;
  uint height;
  uint tileSize;
  uint tilesX;
  uint tilesY;
  uint samples;
  uint seed;
  uint flags;  // HMB_GATHER_FLAG_*
  float velocityScale;
  float softZExtent;
  float foregroundBoost;       // multiplies w_f where z_t - z_s >= softZExtent (when foregroundBoostPixels is 0)
  float maskBackgroundBoost;   // the weights composite: multiplies w_b inside the mask
  float maskForegroundDivide;  // the weights composite: divides w_f inside the mask
  float maxSpeed;              // the coverage composite and the ray mask: v_X clamped to this length (the
                               // image's larger side)
  float foregroundBoostPixels;  // k > 0: w_f's boost is max(1, k / max(|v_N|, 1 px)) per pixel instead (k
                                // already divided by the time slices)
  uint pad2;
};

struct JimenezParams {
  uint width;
  uint height;
  uint tileSize;
  uint tilesX;
  uint tilesY;
  uint samples;  // taken as ceil(samples / 2) mirrored pairs
  uint seed;
  uint pad0;
  float velocityScale;  // E * fps / 2: the notes' filter is centred on the pixel
  float softZExtent;    // depth scale of the soft depth comparison
  float tileJitter;     // neighbour-max lookup offset, up to +- this many tiles per axis
  uint pad1;
};
HMB_GPU_END
HMB_CHECK_SIZE(GatherBlockList, 16)
HMB_CHECK_SIZE(GatherBlockCounters, 32)
HMB_CHECK_SIZE(GatherBlocksParams, 32)
HMB_CHECK_SIZE(StillBlocksParams, 16)
HMB_CHECK_SIZE(TileMaxParams, 32)
HMB_CHECK_SIZE(NeighborMaxParams, 16)
HMB_CHECK_SIZE(GatherParams, 64)
HMB_CHECK_SIZE(JimenezParams, 48)

#endif
