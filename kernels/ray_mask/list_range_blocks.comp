#version 450
// Ray mask: the 8 x 8 blocks of the moving tiles whose pixels can meet the edge mask, listed
// for range_check, a lane per block of the moving tiles (the blocks of each listed tile in turn).
// The tile-max's speed bounds every pixel's of its tile when under the tile
// size (else it was clamped: no bound); a straight walk at speed r visits pixels within
// ceil(r) + 1 of its own, and an edge pixel's own coarse block is flagged (edge_mask), so a
// block with no flagged coarse block that near has no pixel in the mask. Along curved paths
// the reach is not the tile-max's: every block is listed. Listed apart so that the range
// check's groups reach only these blocks: a CPU device runs every branch for every lane, and a
// test within the range check's loop saved nothing; a GPU runs no group for the others.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../mblur/mblur_layout.h"

layout(local_size_x = HMB_RANGE_BLOCKS_GROUP) in;

layout(std430, binding = HMB_RANGE_BLOCKS_BINDING_TILES) readonly buffer Tiles { uint tiles[]; };
layout(std430, binding = HMB_RANGE_BLOCKS_BINDING_TILE_MAX) readonly buffer TileMax { vec4 tileMax[]; };
// The edge mask, then the coarse one (HMB_EDGE_BLOCKS_FIRST).
layout(std430, binding = HMB_RANGE_BLOCKS_BINDING_EDGES) readonly buffer Edges { uint edges[]; };
layout(std430, binding = HMB_RANGE_BLOCKS_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_RANGE_BLOCKS_BINDING_LIST) writeonly buffer Blocks { uint blockList[]; };
layout(push_constant) uniform Params { RayMaskParams params; };

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

// Whether a flagged coarse block lies within `margin` pixels of the 8 x 8 block at `origin`
// (clipped to the image); true, untested, when that is more than testSide coarse blocks a side.
bool edgeBlockNear(uvec2 origin, int margin, int testSide) {
  const ivec2 last = ivec2(int(params.blur.width) - 1, int(params.blur.height) - 1);
  const ivec2 from = clamp(ivec2(origin) - margin, ivec2(0), last) / int(HMB_EDGE_BLOCK);
  const ivec2 to =
      clamp(ivec2(origin) + ivec2(HMB_MASK_TILE_GROUP_X - 1, HMB_MASK_TILE_GROUP_Y - 1) + margin, ivec2(0), last) /
      int(HMB_EDGE_BLOCK);
  if (any(greaterThan(to - from, ivec2(testSide - 1)))) return true;
  // A row's blocks from.x..to.x (at most testSide < 32 of them) lie in one word or two.
  const uint fromBit = uint(from.x) % 32u, toBit = uint(to.x) % 32u;
  const bool oneWord = uint(from.x) / 32u == uint(to.x) / 32u;
  const uint fromBits = ~0u << fromBit, toBits = ~0u >> (31u - toBit);
  for (int y = from.y; y <= to.y; ++y) {
    const uint first = edges[HMB_EDGE_BLOCK_WORD(params.blur.width, params.blur.height, uint(from.x), uint(y))];
    const uint last = edges[HMB_EDGE_BLOCK_WORD(params.blur.width, params.blur.height, uint(to.x), uint(y))];
    if ((oneWord ? first & fromBits & toBits : (first & fromBits) | (last & toBits)) != 0u) return true;
  }
  return false;
}

void main() {
  const uint tileSize = params.blur.tileSize;
  const uint blocks = tileBlocks(tileSize);
  const uint entry = linearInvocationIndex(HMB_RANGE_BLOCKS_GROUP);
  if (entry >= counters.tileCount * blocks) return;
  const uint tile = tiles[entry / blocks];
  const uint block = entry % blocks;
  const uvec2 origin = tileBlockOrigin(tile, block, params.blur.tilesX, tileSize);
  // Blocks past the image's edge (a border tile's) have no pixel.
  const uvec2 tileEnd = min(tileOrigin(tile, params.blur.tilesX, tileSize) + tileSize,
                            uvec2(params.blur.width, params.blur.height));
  if (any(greaterThanEqual(origin, tileEnd))) return;
  const float reach = tileMax[tile].z;
  const bool bounded = (params.blur.flags & HMB_GATHER_FLAG_CURVED_PATH) == 0u && reach < float(tileSize);
  const int margin = bounded ? int(ceil(reach)) + 1 : 0;
  const uint across = tileBlocksAcross(tileSize);
  if (!bounded || edgeBlockNear(origin, margin, int(HMB_RANGE_BLOCKS_MAX_TEST_SIDE)))
    blockList[atomicAdd(counters.rangeBlockCount, 1u)] =
        rangeBlockEntry(origin, block % across == across - 1u, block / across == tileBlocksDown(tileSize) - 1u);
}
