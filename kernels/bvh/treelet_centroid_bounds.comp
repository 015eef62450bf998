#version 450
// The treelet builder's first pass (treelet_build_layout.h), a group per tile: the bounds of its
// primitives' centroids, merged into its tree's with atomics on ordered floats.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "../shared/ordered_float.glsl"
#include "treelet_common.glsl"

layout(local_size_x = HMB_TREELET_SORT_GROUP) in;
layout(std430, binding = HMB_TREELET_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
layout(std430, binding = HMB_TREELET_BINDING_TILES) readonly buffer Tiles { TreeletTile tiles[]; };
layout(std430, binding = HMB_TREELET_BINDING_TREES) buffer Trees { TreeletTree trees[]; };
layout(push_constant) uniform Params { TreeletBuildParams params; };

shared uint low[3];
shared uint high[3];

void main() {
  const uint tileIndex = foldedGroupIndex(), lane = gl_LocalInvocationIndex;
  if (tileIndex >= params.tileCount) return;  // uniform across the group
  const TreeletTile tile = tiles[tileIndex];
  if (lane < 3u) {
    low[lane] = kOrderedPositiveInfinity;
    high[lane] = kOrderedNegativeInfinity;
  }
  barrier();
  vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
  for (uint k = lane; k < tile.count; k += HMB_TREELET_SORT_GROUP) {
    const vec3 c = treeletCentroid(boxes[tile.first + k]);
    lo = min(lo, c);
    hi = max(hi, c);
  }
  for (uint a = 0u; a < 3u; ++a) {
    atomicMin(low[a], orderedUint(lo[a]));
    atomicMax(high[a], orderedUint(hi[a]));
  }
  barrier();
  if (lane < 3u) {
    atomicMin(trees[tile.tree].centroidLow[lane], low[lane]);
    atomicMax(trees[tile.tree].centroidHigh[lane], high[lane]);
  }
}
