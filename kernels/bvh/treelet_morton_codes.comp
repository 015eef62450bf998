#version 450
// The treelet builder's second pass (treelet_build_layout.h), a group per tile: each primitive's
// 30-bit Morton code in its tree's centroid bounds (1024 cells an axis; a flat axis puts every
// centroid in cell 0), the primitive beside it, and the tile's count of each first digit for the
// sort's first pass.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "../shared/ordered_float.glsl"
#include "linear_bvh_layout.h"
#include "treelet_common.glsl"

layout(local_size_x = HMB_TREELET_SORT_GROUP) in;
layout(std430, binding = HMB_TREELET_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
layout(std430, binding = HMB_TREELET_BINDING_TILES) readonly buffer Tiles { TreeletTile tiles[]; };
layout(std430, binding = HMB_TREELET_BINDING_TREES) readonly buffer Trees { TreeletTree trees[]; };
layout(std430, binding = HMB_TREELET_BINDING_KEYS) writeonly buffer Keys { uint keys[]; };
layout(std430, binding = HMB_TREELET_BINDING_VALUES) writeonly buffer Values { uint values[]; };
layout(std430, binding = HMB_TREELET_BINDING_DIGIT_COUNTS) writeonly buffer DigitCounts { uint digitCounts[]; };
layout(push_constant) uniform Params { TreeletBuildParams params; };

shared uint counts[HMB_TREELET_DIGITS];

void main() {
  const uint tileIndex = foldedGroupIndex(), lane = gl_LocalInvocationIndex;
  if (tileIndex >= params.tileCount) return;  // uniform across the group
  const TreeletTile tile = tiles[tileIndex];
  const TreeletTree tree = trees[tile.tree];
  counts[lane] = 0u;
  barrier();
  const vec3 low = vec3(orderedFloat(tree.centroidLow[0]), orderedFloat(tree.centroidLow[1]),
                        orderedFloat(tree.centroidLow[2]));
  const vec3 high = vec3(orderedFloat(tree.centroidHigh[0]), orderedFloat(tree.centroidHigh[1]),
                         orderedFloat(tree.centroidHigh[2]));
  precise const vec3 extent = high - low;
  const bvec3 spread = greaterThan(extent, vec3(0.0));  // false on a flat axis, and where no box is finite
  precise const vec3 scale = mix(vec3(0.0), 1024.0 / extent, spread);
  for (uint k = lane; k < tile.count; k += HMB_TREELET_SORT_GROUP) {
    const uint place = tile.first + k;
    precise const vec3 t = mix(vec3(0.0), (treeletCentroid(boxes[place]) - low) * scale, spread);
    const uint code = mortonCode(uvec3(clamp(t, vec3(0.0), vec3(1023.0))));
    keys[place] = code;
    values[place] = place;
    atomicAdd(counts[code & (HMB_TREELET_DIGITS - 1u)], 1u);
  }
  barrier();
  digitCounts[tileIndex * HMB_TREELET_DIGITS + lane] = counts[lane];
}
