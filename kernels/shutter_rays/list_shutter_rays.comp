#version 450
// Lists the pixels a single frame cannot blur right, with the rays each will take over the
// shutter (trace_shutter_rays). A gather reads one frame, whose edges are sampled at pixel
// centres: where an edge sweeps over a pixel during the shutter, the reference sees it pass
// through sub-pixel positions that frame never held (the error of bistro's moving camera: a
// few pixels of blur at every silhouette). Listed: a pixel whose path meets another object or
// a colour step (HMB_SHUTTER_RAY_COLOR_STEP: a texture's or the shading's edge on one object),
// the path X + u v for u in [-1, 1] and a pixel on at each end, v its own displacement when it
// moves half a pixel or more, else its tile's fastest (a still pixel a moving neighbour may
// sweep over). Its rays: shutterRaysFor the faster of its own and its tile's fastest blur.
// With a ray budget (params.ranks) the path is walked whole for the pixel's priority
// (shutterRayPriority), whose bucket is written beside its entry and whose rays are counted into
// the budget's histogram (select_ray_budget reads it).
// A lane per pixel of the moving tiles' 8 x 8 blocks (list_moving_tiles), a block per group or
// a run of blocks per group (size_list_dispatch, shutter_rays_layout.h); pixels of still tiles are
// never listed.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "shutter_rays_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_MASK_TILE_GROUP_X, local_size_y = HMB_MASK_TILE_GROUP_Y) in;

// The G-buffer's surfaces (object id, velocity) and samples (colour): shared/layer_layout.h,
// read as uniform texel buffers (shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_SHUTTER_LIST_BINDING_SURFACES) uniform utextureBuffer surfaceTexels;
layout(binding = HMB_SHUTTER_LIST_BINDING_SAMPLES) uniform utextureBuffer sampleTexels;
uvec4 surfaceAt(uint index) { return recordAt(surfaceTexels, index); }
uvec4 sampleAt(uint index) { return recordAt(sampleTexels, index); }
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_TILE_MAX) readonly buffer TileMax { vec4 tileMax[]; };
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_TILES) readonly buffer Tiles { uint tiles[]; };
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_COUNTERS) buffer Counters { ShutterRayCounters counters; };
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_LIST) writeonly buffer List { uint list[]; };
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_MASK_COUNTERS) readonly buffer MaskCounters {
  RayMaskCounters maskCounters;
};
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_PRIORITIES) writeonly buffer Priorities { uint priorities[]; };
layout(std430, binding = HMB_SHUTTER_LIST_BINDING_BUDGET) buffer Budget { ShutterRayBudget budget; };
layout(push_constant) uniform Params { ShutterRayListParams params; };

#include "../mblur/mblur_common.glsl"
#include "../ray_mask/ray_mask_common.glsl"

// How far pixel p's look is from a pixel of object `id` and colour key `key`: -1 when it shows
// the same object within a colour step, else the largest step of the keys' channels.
float difference(ivec2 p, uint id, vec3 key) {
  const uint index = uint(p.y) * params.blur.width + uint(p.x);
  const vec3 there = shutterRayColorKey(sampleColor(sampleAt(index)));
  const vec3 step = abs(there - key);
  const float contrast = max(step.x, max(step.y, step.z));
  return surfaceObjectId(surfaceAt(index)) != id || shutterRayColorsDiffer(there, key) ? contrast : -1.0;
}

struct Listing {
  uint rays;      // 0: not listed
  uint priority;  // its bucket (ranked lists only)
};

// The rays pixel `pixel` takes, and their priority. fastest: its tile's (velocity, speed).
Listing shutterRaysAt(ivec2 pixel, vec3 fastest) {
  const uint index = uint(pixel.y) * params.blur.width + uint(pixel.x);
  const uvec4 here = surfaceAt(index);
  const uint id = surfaceObjectId(here);
  const vec3 key = shutterRayColorKey(sampleColor(sampleAt(index)));
  float speed;
  const vec2 own = gatherVelocity(surfaceVelocity(here), params.blur.velocityScale, params.blur.maxSpeed, speed);
  const bool moves = speed >= 0.5;
  const vec2 v = moves ? own : fastest.xy;
  const float length = moves ? speed : fastest.z;
  // Steps of at most a pixel over the path and a pixel past either end; without a budget the
  // walk ends at the first sample that differs.
  const vec2 reach = v * (1.0 + 1.0 / length);
  const int steps = int(ceil(length + 1.0));
  const vec2 centre = vec2(pixel) + 0.5;
  const bool whole = params.ranks != 0u;
  uint differing = 0u;
  float contrast = 0.0;
  for (int k = 1; k <= steps && (whole || differing == 0u); ++k) {
    const vec2 along = reach * (float(k) / float(steps));
    const float ahead = difference(nearestPixel(centre + along, params.blur.width, params.blur.height), id, key);
    const float behind = difference(nearestPixel(centre - along, params.blur.width, params.blur.height), id, key);
    differing += uint(ahead >= 0.0) + uint(behind >= 0.0);
    contrast = max(contrast, max(ahead, behind));
  }
  Listing listing;
  listing.rays = differing != 0u ? shutterRaysFor(max(speed, fastest.z), params.strata) : 0u;
  listing.priority =
      shutterRayPriorityBucket(shutterRayPriority(contrast, differing, 2u * uint(steps), listing.rays));
  return listing;
}

// Lists `pixel` with its rays; the list's dispatch grows with it, a group per
// HMB_MASK_LIST_GROUP entries.
void listPixel(uvec2 pixel, Listing listing) {
  const uint slot = atomicAdd(counters.count, 1u);
  list[slot] = shutterRayEntry(pixel.y * params.blur.width + pixel.x, listing.rays);
  if (params.ranks != 0u) {
    priorities[slot] = listing.priority;
    atomicAdd(budget.histogram[listing.priority], listing.rays / 2u);
  }
  if (slot % HMB_MASK_LIST_GROUP != 0u) return;
  const uint group = slot / HMB_MASK_LIST_GROUP;
  atomicMax(counters.dispatchX, min(group + 1u, HMB_SHUTTER_RAY_GROUPS_PER_ROW));
  atomicMax(counters.dispatchY, group / HMB_SHUTTER_RAY_GROUPS_PER_ROW + 1u);
  if (group == 0u) counters.dispatchZ = 1u;
}

void main() {
  // The blocks of every moving tile in turn, tileBlocks() to a tile; this group's run of them,
  // taken a tile at a time so the divisions that place a block run once a tile.
  const uint tileSize = params.blur.tileSize;
  const uint perTile = tileBlocks(tileSize);
  const uint blocksX = tileBlocksAcross(tileSize);
  const uvec2 run = groupRun(maskCounters.tileCount * perTile);
  uint entry = run.x;
  const uint end = run.y;
  while (entry < end) {
    const uint listed = entry / perTile;
    const uint tile = tiles[listed];
    const uvec2 corner = tileOrigin(tile, params.blur.tilesX, tileSize);
    const uvec2 tileEnd = min(corner + tileSize, uvec2(params.blur.width, params.blur.height));
    // A moving tile's fastest moves kMinBlurPixels or more (list_moving_tiles).
    const vec3 fastest = tileMax[tile].xyz;
    const uint block = entry - listed * perTile;
    uvec2 at = uvec2(block % blocksX, block / blocksX);
    for (const uint last = min(end, (listed + 1u) * perTile); entry < last; ++entry) {
      const uvec2 pixel = corner + at * uvec2(HMB_MASK_TILE_GROUP_X, HMB_MASK_TILE_GROUP_Y) + gl_LocalInvocationID.xy;
      at = at.x + 1u == blocksX ? uvec2(0u, at.y + 1u) : uvec2(at.x + 1u, at.y);
      // Lanes past the tile's or the image's edge have no pixel.
      if (any(greaterThanEqual(pixel, tileEnd))) continue;
      const Listing listing = shutterRaysAt(ivec2(pixel), fastest);
      if (listing.rays != 0u) listPixel(pixel, listing);
    }
  }
}
