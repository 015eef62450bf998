#version 450
// Tile-max (McGuire et al. 2012, the paper's tile-dilate first step): for each m x m tile, the
// gather velocity of largest magnitude among its pixels, each pixel's velocity converted and
// clamped to m first (mblur_common.glsl). Tiles at the right and bottom borders are partial.
// Ties go to the pixel first in row-major image order, whatever order the lanes ran in.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_TILE_MAX_GROUP_X, local_size_y = HMB_TILE_MAX_GROUP_Y) in;

layout(std430, binding = HMB_TILE_MAX_BINDING_SURFACES) readonly buffer Surfaces { uvec4 surfaces[]; };
layout(std430, binding = HMB_TILE_MAX_BINDING_TILES) writeonly buffer Tiles { vec4 tiles[]; };
layout(push_constant) uniform Params { TileMaxParams params; };

#include "mblur_common.glsl"

const uint kLanes = HMB_TILE_MAX_GROUP_X * HMB_TILE_MAX_GROUP_Y;
shared vec2 laneVelocity[kLanes];
shared float laneSpeed[kLanes];
shared uint lanePixel[kLanes];

// Larger speed wins; equal speeds go to the smaller pixel index.
bool better(float speedA, uint indexA, float speedB, uint indexB) {
  return speedA > speedB || (speedA == speedB && indexA < indexB);
}

void main() {
  const uvec2 tile = gl_WorkGroupID.xy;
  const uvec2 lane = gl_LocalInvocationID.xy;
  const uint m = params.tileSize;
  const uvec2 begin = tile * m;
  const uvec2 end = min(begin + m, uvec2(params.width, params.height));

  vec2 bestVelocity = vec2(0.0);
  float bestSpeed = -1.0;
  uint bestIndex = 0xFFFFFFFFu;
  for (uint y = begin.y + lane.y; y < end.y; y += HMB_TILE_MAX_GROUP_Y) {
    for (uint x = begin.x + lane.x; x < end.x; x += HMB_TILE_MAX_GROUP_X) {
      const uint index = y * params.width + x;
      float speed;
      const vec2 v = gatherVelocity(surfaceVelocity(surfaces[index]), params.velocityScale, float(m), speed);
      if (better(speed, index, bestSpeed, bestIndex)) {
        bestVelocity = v;
        bestSpeed = speed;
        bestIndex = index;
      }
    }
  }
  const uint laneIndex = lane.y * HMB_TILE_MAX_GROUP_X + lane.x;
  laneVelocity[laneIndex] = bestVelocity;
  laneSpeed[laneIndex] = bestSpeed;
  lanePixel[laneIndex] = bestIndex;
  barrier();
  if (laneIndex != 0u) return;

  for (uint i = 1u; i < kLanes; ++i) {
    if (better(laneSpeed[i], lanePixel[i], bestSpeed, bestIndex)) {
      bestVelocity = laneVelocity[i];
      bestSpeed = laneSpeed[i];
      bestIndex = lanePixel[i];
    }
  }
  tiles[tile.y * params.tilesX + tile.x] = vec4(bestVelocity, max(bestSpeed, 0.0), 0.0);
}
