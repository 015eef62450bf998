#version 450
// Sorts the gather's 8 x 8 blocks (mblur_layout.h, HMB_GATHER_BLOCK) into moving and still:
// still where every tile its pixels lie in has a neighbour-max speed under kMinBlurPixels, the
// test the gather makes per pixel. The moving blocks fill the list from its front, the still
// ones from its back, each in no order; the counters end as the indirect dispatches of the two.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "mblur_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_GATHER_BLOCKS_GROUP) in;

layout(std430, binding = HMB_GATHER_BLOCKS_BINDING_NEIGHBOR_MAX) readonly buffer NeighborMax { vec4 neighborMax[]; };
layout(std430, binding = HMB_GATHER_BLOCKS_BINDING_COUNTERS) buffer Counters { GatherBlockCounters counters; };
layout(std430, binding = HMB_GATHER_BLOCKS_BINDING_LIST) writeonly buffer List { uint blocks[]; };
layout(push_constant) uniform Params { GatherBlocksParams params; };

void main() {
  const uint block = linearInvocationIndex(HMB_GATHER_BLOCKS_GROUP);
  if (block >= params.blockCount) return;
  const uvec2 place = uvec2(block % params.blocksX, block / params.blocksX);
  const uvec2 first = place * HMB_GATHER_BLOCK;
  const uvec2 last = min(first + (HMB_GATHER_BLOCK - 1u), uvec2(params.width, params.height) - 1u);
  // A tile size under the block's covers it with up to 8 x 8 tiles; at least 8, 2 x 2.
  bool moving = false;
  for (uint y = first.y / params.tileSize; y <= last.y / params.tileSize; ++y)
    for (uint x = first.x / params.tileSize; x <= last.x / params.tileSize; ++x)
      moving = moving || !(neighborMax[y * params.tilesX + x].z < kMinBlurPixels);  // NaN: moving, as the gather
  // The moving blocks fill the list from its front, the still ones from its back; each list's
  // dispatch grows with it, HMB_GATHER_BLOCKS_PER_ROW groups to a row.
  const uint list = moving ? HMB_GATHER_BLOCKS_MOVING : HMB_GATHER_BLOCKS_STILL;
  const uint slot = atomicAdd(counters.lists[list].count, 1u);
  blocks[moving ? slot : params.blockCount - 1u - slot] = gatherBlockEntry(place);
  if (slot < HMB_GATHER_BLOCKS_PER_ROW) atomicMax(counters.lists[list].dispatchX, slot + 1u);
  if (slot % HMB_GATHER_BLOCKS_PER_ROW == 0u) atomicMax(counters.lists[list].dispatchY, slot / HMB_GATHER_BLOCKS_PER_ROW + 1u);
  if (slot == 0u) counters.lists[list].dispatchZ = 1u;
}
