// Tile-max's reduction (McGuire et al. 2012), shared by the gather's tile_max.comp and the
// hybrid's tile_max_edge_candidates.comp, which also tests the tile's pixels.
// The including kernel declares `tiles[]` (vec4 per tile, mblur_layout.h), and defines, before
// this file,
//   vec2 tileVelocityAt(uint index)  // the G-buffer's velocity at a pixel (its velocities: shared/layer_layout.h)
//   void visitTilePixel(uvec2 pixel, uint index, GatherVelocityParts velocity, float speed)
// the latter called once per pixel of the tile with its gather velocity's parts and its speed
// clamped to the tile size.
// Include after mblur_common.glsl; the group is HMB_TILE_MAX_GROUP_X x HMB_TILE_MAX_GROUP_Y.
#ifndef HMB_KERNELS_MBLUR_TILE_MAX_REDUCTION_GLSL
#define HMB_KERNELS_MBLUR_TILE_MAX_REDUCTION_GLSL

const uint kTileMaxLanes = HMB_TILE_MAX_GROUP_X * HMB_TILE_MAX_GROUP_Y;
shared vec2 laneVelocity[kTileMaxLanes];
shared float laneSpeed[kTileMaxLanes];
shared uint lanePixel[kTileMaxLanes];
shared float reducedTileSpeed;

// Larger speed wins; equal speeds go to the smaller pixel index.
bool better(float speedA, uint indexA, float speedB, uint indexB) {
  return speedA > speedB || (speedA == speedB && indexA < indexB);
}

// For tile `tile` (m x m pixels; partial at the right and bottom borders), the gather velocity
// of largest magnitude among its pixels, each converted and clamped to m first; ties go to the
// pixel first in row-major image order, whatever order the lanes ran in. One group per tile.
// Returns the tile's speed (as written) to every lane when toEveryLane, else to lane 0 alone
// (0 to the others), which saves the group a barrier.
float reduceTileMax(uvec2 tile, uint width, uint height, uint m, uint tilesX, float velocityScale, bool toEveryLane) {
  const uvec2 lane = gl_LocalInvocationID.xy;
  const uvec2 begin = tile * m;
  const uvec2 end = min(begin + m, uvec2(width, height));

  vec2 bestVelocity = vec2(0.0);
  float bestSpeed = -1.0;
  uint bestIndex = 0xFFFFFFFFu;
  for (uint y = begin.y + lane.y; y < end.y; y += HMB_TILE_MAX_GROUP_Y) {
    for (uint x = begin.x + lane.x; x < end.x; x += HMB_TILE_MAX_GROUP_X) {
      const uint index = y * width + x;
      const GatherVelocityParts parts = gatherVelocityParts(tileVelocityAt(index), velocityScale);
      float speed;
      const vec2 v = clampedGatherVelocity(parts, float(m), speed);
      visitTilePixel(uvec2(x, y), index, parts, speed);
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
  if (laneIndex == 0u) {
    for (uint i = 1u; i < kTileMaxLanes; ++i) {
      if (better(laneSpeed[i], lanePixel[i], bestSpeed, bestIndex)) {
        bestVelocity = laneVelocity[i];
        bestSpeed = laneSpeed[i];
        bestIndex = lanePixel[i];
      }
    }
    reducedTileSpeed = max(bestSpeed, 0.0);
    tiles[tile.y * tilesX + tile.x] = vec4(bestVelocity, reducedTileSpeed, 0.0);
  }
  if (!toEveryLane) return laneIndex == 0u ? reducedTileSpeed : 0.0;  // the others may not see it yet
  barrier();
  return reducedTileSpeed;
}

#endif
