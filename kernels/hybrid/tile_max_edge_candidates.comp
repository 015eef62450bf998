#version 450
// The hybrid's tile-max: the gather's tile-max (mblur/tile_max_reduction.glsl), and, while each
// pixel's surface is in hand, the ray mask's first test (paper, eqs. 1, 2): list the moving
// pixels whose predicted end position lies on a different object deeper by more than
// SOFT_Z_EXTENT. Only these can enter the edge mask, and they are few (bistro: 3% of its
// pixels), so edge_mask runs its Sobel over this list with every lane busy. One read of the
// G-buffer's surfaces serves both: a pass of its own read them all again (bistro at 1280x720 on
// a CPU device: tile-max 6 ms, the separate candidates pass 12).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "hybrid_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_TILE_MAX_GROUP_X, local_size_y = HMB_TILE_MAX_GROUP_Y) in;

// The G-buffer's samples (depth) and surfaces (velocity, object id): shared/layer_layout.h.
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_SAMPLES) readonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_SURFACES) readonly buffer Surfaces { uvec4 surfaces[]; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_TILE_MAX) writeonly buffer Tiles { vec4 tiles[]; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_TILE_MAX_CANDIDATES_BINDING_LIST) writeonly buffer Candidates { uint candidates[]; };
layout(push_constant) uniform Params { RayMaskParams params; };

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

// Eqs. 1 and 2 at one pixel. tileV, tileSpeed: its velocity clamped to the tile size; the
// ranges are clamped to params.blur.maxSpeed (the image's side), the same velocity unless
// either clamp acts.
void visitTilePixel(uvec2 pixel, uint index, uvec4 surface, vec2 tileV, float tileSpeed) {
  if (!(tileSpeed > 0.0)) return;
  vec2 v = tileV;
  if (!(tileSpeed < float(params.blur.tileSize) && tileSpeed <= params.blur.maxSpeed)) {
    float speed;
    v = gatherVelocity(surfaceVelocity(surface), params.blur.velocityScale, params.blur.maxSpeed, speed);
    if (!(speed > 0.0)) return;
  }
  const ivec2 end = nearestPixel(vec2(pixel) + 0.5 + v, params.blur.width, params.blur.height);
  const uint endIndex = uint(end.y) * params.blur.width + uint(end.x);
  // Eq. 1 first: most pixels end on their own object, and their depths need no read.
  const uint idHere = surfaceObjectId(surface), idEnd = surfaceObjectId(surfaces[endIndex]);
  if (idEnd == idHere) return;
  if (endsOnDeeperObject(idHere, sanitizeDepth(sampleDepth(samples[index])), idEnd, sampleDepth(samples[endIndex]),
                         params.blur.softZExtent))
    candidates[atomicAdd(counters.candidateCount, 1u)] = index;
}

#include "../mblur/tile_max_reduction.glsl"

void main() {
  reduceTileMax(gl_WorkGroupID.xy, params.blur.width, params.blur.height, params.blur.tileSize, params.blur.tilesX,
                params.blur.velocityScale);
}
