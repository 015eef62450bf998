#version 450
// The hybrid's tile-max: the gather's tile-max (mblur/tile_max_reduction.glsl), the moving
// tiles listed as it writes them (list_moving_tiles' list, a pass fewer), and the ray mask's
// first test (paper, eqs. 1, 2) at the pixels it reads: list the moving pixels whose
// predicted end position lies on a different object deeper by more than SOFT_Z_EXTENT. Only
// these can enter the edge mask, and they are few (bistro: 3% of its pixels), so edge_mask runs
// its Sobel over this list with every lane busy. A pass of its own read the surfaces again, at a
// cost (bench/results/ray-mask-tile-max/). Where the test runs
// (HMB_SPEC_TILE_MAX_CANDIDATES_IN_LOOP, chosen by the host):
//  - inside the reduction's loop, on the velocity it has in hand: a GPU skips it at still
//    pixels, and where every tile moves (a moving camera) it is the cheapest on a CPU too;
//  - after the reduction, in the tiles that move alone, reading the velocities again: a CPU
//    device runs the code of a branch no lane takes, so in the loop the test cost every pixel of
//    a still tile as much as a moving one's (bench/results/ray-mask-tile-max/).
// Both list exactly the pixels where eqs. 1, 2 hold (kMinCandidateSpeed: the others end on
// their own pixel), each pixel moving by its velocity as the reduction ranks it (the G-buffer's
// velocities, floats).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_TILE_MAX_GROUP_X, local_size_y = HMB_TILE_MAX_GROUP_Y) in;

// The G-buffer's velocities, which the reduction ranks and eqs. 1, 2 follow, and its surfaces
// (object id, depth): shared/layer_layout.h, read as uniform texel buffers
// (shared/texel_records.glsl). Eqs. 1, 2 take the end's id and depth in one load.
#include "../shared/texel_records.glsl"
layout(binding = HMB_TILE_MAX_CANDIDATES_BINDING_VELOCITIES) uniform utextureBuffer velocityTexels;
layout(binding = HMB_TILE_MAX_CANDIDATES_BINDING_SURFACES) uniform utextureBuffer surfaceTexels;
vec2 velocityAt(uint index) { return uintBitsToFloat(halfRecordAt(velocityTexels, index)); }
uvec4 surfaceAt(uint index) { return recordAt(surfaceTexels, index); }
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_TILE_MAX) writeonly buffer Tiles { vec4 tiles[]; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_LIST) writeonly buffer Candidates { uint candidates[]; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_MOVING_TILES) writeonly buffer MovingTiles { uint movingTiles[]; };
layout(push_constant) uniform Params { RayMaskParams params; };
layout(constant_id = HMB_SPEC_TILE_MAX_CANDIDATES_IN_LOOP) const bool kTestInLoop = true;

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

// Eqs. 1 and 2 at a pixel moving by v (clamped to params.blur.maxSpeed, the image's side).
void listIfCandidate(uvec2 pixel, uint index, vec2 v) {
  const ivec2 end = nearestPixel(vec2(pixel) + 0.5 + v, params.blur.width, params.blur.height);
  const uvec4 surface = surfaceAt(index);
  const uvec4 endSurface = surfaceAt(uint(end.y) * params.blur.width + uint(end.x));
  if (endsOnDeeperObject(surfaceObjectId(surface), sanitizeDepth(surfaceDepth(surface)), surfaceObjectId(endSurface),
                         surfaceDepth(endSurface), params.blur.softZExtent))
    candidates[atomicAdd(counters.candidateCount, 1u)] = index;
}

// In the reduction's loop: tileSpeed is the pixel's speed clamped to the tile size, and the
// velocity is clamped again to the image's side, as the ranges clamp it, from the same parts (a
// second gatherVelocity here, under a branch that a CPU device runs at every pixel, cost time).
void visitTilePixel(uvec2 pixel, uint index, GatherVelocityParts velocity, float tileSpeed) {
  if (!kTestInLoop || !(tileSpeed >= kMinCandidateSpeed)) return;
  float speed;
  listIfCandidate(pixel, index, clampedGatherVelocity(velocity, params.blur.maxSpeed, speed));
}

vec2 tileVelocityAt(uint index) { return velocityAt(index); }

#include "../mblur/tile_max_reduction.glsl"

void main() {
  const uvec2 tile = gl_WorkGroupID.xy;
  const float tileSpeed = reduceTileMax(tile, params.blur.width, params.blur.height, params.blur.tileSize,
                                        params.blur.tilesX, params.blur.velocityScale, !kTestInLoop);
  // Lane 0 has the tile's speed either way; NaN speeds never reach here (sanitized).
  if (gl_LocalInvocationIndex == 0u && tileSpeed >= kMinBlurPixels)
    movingTiles[atomicAdd(counters.tileCount, 1u)] = tile.y * params.blur.tilesX + tile.x;
  // After the loop: a tile whose pixels all end on themselves has no candidate.
  if (kTestInLoop || !(tileSpeed >= kMinCandidateSpeed)) return;
  const uvec2 begin = tile * params.blur.tileSize;
  const uvec2 end = min(begin + params.blur.tileSize, uvec2(params.blur.width, params.blur.height));
  for (uint y = begin.y + gl_LocalInvocationID.y; y < end.y; y += HMB_TILE_MAX_GROUP_Y) {
    for (uint x = begin.x + gl_LocalInvocationID.x; x < end.x; x += HMB_TILE_MAX_GROUP_X) {
      const uint index = y * params.blur.width + x;
      float speed;
      const vec2 v = gatherVelocity(velocityAt(index), params.blur.velocityScale, params.blur.maxSpeed, speed);
      if (speed >= kMinCandidateSpeed) listIfCandidate(uvec2(x, y), index, v);
    }
  }
}
