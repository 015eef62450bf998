#version 450
// Ray mask, second pass (paper, section 3.2.1, range check): a moving pixel enters the ray
// mask when its range X + u v, u in [0, 1], meets the edge mask: it is then in the inner blur
// of a silhouette, where the raster holds no background. The range is walked one pixel at a
// time (ceil |v| + 1 positions), so an edge band of any width is found. Masked pixels are
// appended to a list (compaction) whose length sizes the ray reveal's indirect dispatch. Runs
// over the moving tiles only (list_moving_tiles); the mask is 0 elsewhere.
#extension GL_GOOGLE_include_directive : require
#include "hybrid_layout.h"
#include "../mblur/mblur_layout.h"

layout(local_size_x = HMB_MASK_TILE_GROUP_X, local_size_y = HMB_MASK_TILE_GROUP_Y) in;

layout(std430, binding = HMB_RANGE_CHECK_BINDING_VELOCITY) readonly buffer Velocity { vec2 velocity[]; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_EDGES) readonly buffer Edges { uint edges[]; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_TILES) readonly buffer Tiles { uint tiles[]; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_MASK) writeonly buffer Mask { uint mask[]; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_RANGE_CHECK_BINDING_LIST) writeonly buffer List { uint list[]; };
layout(push_constant) uniform Params { RangeCheckParams params; };

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

// The range check at one pixel.
uint maskedAt(uvec2 pixel) {
  float speed;
  const vec2 v = gatherVelocity(velocity[pixel.y * params.width + pixel.x], params.velocityScale, params.maxSpeed, speed);
  if (!(speed > 0.0)) return 0u;
  const uint steps = uint(ceil(speed));  // <= maxSpeed, the image's larger side
  const vec2 centre = vec2(pixel) + 0.5;
  for (uint i = 0u; i <= steps; ++i) {
    const ivec2 p = nearestPixel(centre + v * (float(i) / float(steps)), params.width, params.height);
    if (edges[uint(p.y) * params.width + uint(p.x)] != 0u) return 1u;
  }
  return 0u;
}

void main() {
  const uvec2 pixel = listedTilePixel(tiles[listedTileEntry()], params.tilesX, params.tileSize);
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const uint masked = maskedAt(pixel);
  mask[index] = masked;
  if (masked != 0u) list[atomicAdd(counters.maskCount, 1u)] = index;
}
