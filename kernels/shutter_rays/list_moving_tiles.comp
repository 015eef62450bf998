#version 450
// The tiles whose fastest pixel moves half a pixel or more over the exposure (the gather's
// tile-max, speeds in its z). Elsewhere every pixel's displacement ends on the pixel itself, so
// no pixel can pass eq. 1 or meet an edge along its range: the mask passes skip those tiles.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "shutter_rays_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_MOVING_TILES_GROUP) in;

layout(std430, binding = HMB_MOVING_TILES_BINDING_TILE_MAX) readonly buffer TileMax { vec4 tileMax[]; };
layout(std430, binding = HMB_MOVING_TILES_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_MOVING_TILES_BINDING_LIST) writeonly buffer List { uint tiles[]; };
layout(push_constant) uniform Params { MovingTilesParams params; };

void main() {
  const uint tile = linearInvocationIndex(HMB_MOVING_TILES_GROUP);
  if (tile >= params.tileCount) return;
  // NaN speeds never reach here: tile_max stores sanitized speeds.
  if (tileMax[tile].z >= kMinBlurPixels) tiles[atomicAdd(counters.tileCount, 1u)] = tile;
}
