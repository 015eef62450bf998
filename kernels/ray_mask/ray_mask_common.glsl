// The ray mask's per-pixel tests (paper, section 3.2.1), shared by its kernels;
// the C++ reference (tests/hybrid/hybrid_reference.cpp) mirrors each function. Include after
// ray_mask_layout.h and kernels/mblur/mblur_common.glsl (velocities are read as the gather reads
// them, so the mask covers exactly the range the gather blurs over).
#ifndef HMB_KERNELS_HYBRID_RAY_MASK_COMMON_GLSL
#define HMB_KERNELS_HYBRID_RAY_MASK_COMMON_GLSL

#include "../shared/indexing.glsl"

// Eqs. 1 and 2: the pixel's predicted position at the other end of its displacement lies on
// another object (m_n != m_t) that is deeper by more than SOFT_Z_EXTENT (z_n - z_t > S).
// Under the shutter convention the pixel sees the points now at X + u v, u in [0, 1], so
// X + v is where its range ends.
bool endsOnDeeperObject(uint idHere, float depthHere, uint idEnd, float depthEnd, float softZExtent) {
  return idEnd != idHere && sanitizeDepth(depthEnd) - sanitizeDepth(depthHere) > softZExtent;
}

// A pixel slower than this ends on itself: X + 1/2 + v stays within a quarter pixel of its
// centre, which rounding cannot carry over a pixel border in an image up to 2^14 pixels a side
// (a float there resolves 2^-10), so eq. 1 fails. The G-buffer's rounding leaves still surfaces
// speeds around 1e-5 px (the living room's): those need no test.
const float kMinCandidateSpeed = 0.25;

// The 5x5 Sobel operator, separable: smoothing (1 4 6 4 1) across, derivative (-1 -2 0 2 1) along.
float sobelSmooth(int k) { return k == 0 ? 6.0 : (abs(k) == 1 ? 4.0 : 1.0); }
float sobelDerivative(int k) { return k == 0 ? 0.0 : float(sign(k)) * (abs(k) == 1 ? 2.0 : 1.0); }

// Eq. 4: x_n = saturate(1 - 1 / (x + 1)) for x = delta_d + delta_n (eq. 3); an infinite x (a
// depth step to an infinitely far background) is the strongest edge, 1.
float normalizedEdge(float x) {
  if (isnan(x)) return 0.0;
  if (isinf(x)) return x > 0.0 ? 1.0 : 0.0;
  return clamp(1.0 - 1.0 / (max(x, 0.0) + 1.0), 0.0, 1.0);
}

// This group's run [x, y) of `count` blocks dealt out in turn over all the dispatch's groups
// (range_check, list_shutter_rays: a block each on a GPU, runs on a CPU device).
uvec2 groupRun(uint count) {
  const uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z;
  const uint run = (count + groups - 1u) / groups;
  const uint begin = foldedGroupIndex() * run;
  return uvec2(begin, min(begin + run, count));
}

// The first pixel of `tile` in a grid tilesX tiles across.
uvec2 tileOrigin(uint tile, uint tilesX, uint tileSize) { return uvec2(tile % tilesX, tile / tilesX) * tileSize; }

// The pixels across and down of a listed block (rangeBlockEntry) inside its tile: 8 x 8, less
// in a tile's last block across or down where the side is no multiple of 8.
uvec2 rangeBlockSide(uint listed, uint tileSize) {
  const uvec2 lastSide = uvec2(tileSize - (tileBlocksAcross(tileSize) - 1u) * HMB_MASK_TILE_GROUP_X,
                               tileSize - (tileBlocksDown(tileSize) - 1u) * HMB_MASK_TILE_GROUP_Y);
  return uvec2((listed & HMB_RANGE_BLOCK_LAST_ACROSS) != 0u ? lastSide.x : HMB_MASK_TILE_GROUP_X,
               (listed & HMB_RANGE_BLOCK_LAST_DOWN) != 0u ? lastSide.y : HMB_MASK_TILE_GROUP_Y);
}
// The first pixel of block `block` of `tile` (tileBlocks() in ray_mask_layout.h).
uvec2 tileBlockOrigin(uint tile, uint block, uint tilesX, uint tileSize) {
  const uint blocksX = tileBlocksAcross(tileSize);
  return tileOrigin(tile, tilesX, tileSize) +
         uvec2(block % blocksX, block / blocksX) * uvec2(HMB_MASK_TILE_GROUP_X, HMB_MASK_TILE_GROUP_Y);
}

#endif
