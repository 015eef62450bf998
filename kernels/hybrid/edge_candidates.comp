#version 450
// Ray mask, first pass (paper, eqs. 1, 2): list the moving pixels whose predicted end position
// lies on a different object deeper by more than SOFT_Z_EXTENT. Only these can enter the edge
// mask, and they are few (bistro: 3% of its pixels), so edge_mask runs its Sobel over this
// list with every lane busy instead of over the image with most lanes idle. One group per
// moving tile (list_moving_tiles), its lanes striding over the tile as tile_max's do.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "hybrid_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_MASK_TILE_GROUP_X, local_size_y = HMB_MASK_TILE_GROUP_Y) in;

// The G-buffer's samples (depth) and surfaces (velocity, object id): shared/layer_layout.h.
layout(std430, binding = HMB_EDGE_CANDIDATES_BINDING_SAMPLES) readonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = HMB_EDGE_CANDIDATES_BINDING_SURFACES) readonly buffer Surfaces { uvec4 surfaces[]; };
layout(std430, binding = HMB_EDGE_CANDIDATES_BINDING_TILES) readonly buffer Tiles { uint tiles[]; };
layout(std430, binding = HMB_EDGE_CANDIDATES_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_EDGE_CANDIDATES_BINDING_LIST) writeonly buffer Candidates { uint candidates[]; };
layout(push_constant) uniform Params { RayMaskParams params; };

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

// Eqs. 1 and 2 at one pixel.
bool isCandidate(uvec2 pixel, uint index) {
  const uvec4 here = surfaces[index];
  float speed;
  const vec2 v = gatherVelocity(surfaceVelocity(here), params.blur.velocityScale, params.blur.maxSpeed, speed);
  if (!(speed > 0.0)) return false;
  const ivec2 end = nearestPixel(vec2(pixel) + 0.5 + v, params.blur.width, params.blur.height);
  const uint endIndex = uint(end.y) * params.blur.width + uint(end.x);
  return endsOnDeeperObject(surfaceObjectId(here), sanitizeDepth(sampleDepth(samples[index])),
                            surfaceObjectId(surfaces[endIndex]), sampleDepth(samples[endIndex]), params.blur.softZExtent);
}

void main() {
  const uint tile = tiles[listedTileEntry()];
  const uvec2 begin = tileOrigin(tile, params.blur.tilesX, params.blur.tileSize);
  const uvec2 end = min(begin + params.blur.tileSize, uvec2(params.blur.width, params.blur.height));
  for (uint y = begin.y + gl_LocalInvocationID.y; y < end.y; y += HMB_MASK_TILE_GROUP_Y) {
    for (uint x = begin.x + gl_LocalInvocationID.x; x < end.x; x += HMB_MASK_TILE_GROUP_X) {
      const uint index = y * params.blur.width + x;
      if (isCandidate(uvec2(x, y), index)) candidates[atomicAdd(counters.candidateCount, 1u)] = index;
    }
  }
}
