// What the BVH build kernels share: their bindings, and how a box yields the centroid it is
// binned and partitioned by.
#ifndef HMB_KERNELS_BVH_BVH_BUILD_COMMON_GLSL
#define HMB_KERNELS_BVH_BVH_BUILD_COMMON_GLSL

#include "bvh_build_layout.h"
#include "packed_node.glsl"

// Primitive boxes are read at per-lane addresses through a uniform texel buffer (two records a
// box: ../shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_BUILD_BINDING_BOXES) uniform utextureBuffer boxTexels;
layout(std430, binding = HMB_BUILD_BINDING_ROOTS) readonly buffer Roots { uvec2 roots[]; };
layout(std430, binding = HMB_BUILD_BINDING_PRIMITIVES) buffer Primitives { uint primitives[]; };
// A kernel whose lanes read, within one dispatch, what others wrote (insert_primitives) defines
// HMB_BVH_BUILD_COHERENT as `coherent` before including this file.
#ifndef HMB_BVH_BUILD_COHERENT
#define HMB_BVH_BUILD_COHERENT
#endif
layout(std430, binding = HMB_BUILD_BINDING_NODES) HMB_BVH_BUILD_COHERENT buffer Nodes { BvhNode nodes[]; };
layout(std430, binding = HMB_BUILD_BINDING_TASKS) HMB_BVH_BUILD_COHERENT buffer Tasks {
  BvhBuildCounters counters;
  BvhBuildTask tasks[];
};
layout(std430, binding = HMB_BUILD_BINDING_PACKED_NODES) buffer PackedNodes { uvec4 packedNodes[]; };
layout(std430, binding = HMB_BUILD_BINDING_FRAMES) buffer Frames { BvhFrame frames[]; };
layout(push_constant) uniform Params { BvhBuildParams params; };

BvhBox boxAt(uint primitive) {
  BvhBox box;
  box.min = floatRecordAt(boxTexels, 2u * primitive);
  box.max = floatRecordAt(boxTexels, 2u * primitive + 1u);
  return box;
}

// The centre of an empty box (a primitive with no area to hit) is the origin, as on the host
// (Aabb::center): it still needs a place in the tree, and adds nothing to any node's bounds.
vec3 centroidOf(BvhBox box) {
  return all(lessThanEqual(box.min.xyz, box.max.xyz)) ? 0.5 * (box.min.xyz + box.max.xyz) : vec3(0.0);
}

float surfaceArea(vec3 lo, vec3 hi) {
  const vec3 e = max(hi - lo, vec3(0.0));
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// A new child node over primitives first..first+count-1 with bounds lo..hi, exact and packed in
// its tree's frame (or marked to be packed later: HMB_SPEC_BVH_PACK_LATER); a child of one
// primitive is a leaf at once (the others get their index word when they are split or made
// leaves).
void writeChild(uint index, uint first, uint count, uint tree, vec3 lo, vec3 hi, bool packLater) {
  BvhNode child;
  child.minX = lo.x;
  child.minY = lo.y;
  child.minZ = lo.z;
  child.maxX = hi.x;
  child.maxY = hi.y;
  child.maxZ = hi.z;
  child.leftOrFirst = first;
  child.count = count == 1u ? 1u : 0u;
  nodes[index] = child;
  if (packLater) packedNodes[index] = uvec4(HMB_BVH_PACK_LATER, tree, 0u, packLeftOrFirstCount(first, child.count));
  else packedNodes[index] = uvec4(packBox(lo, hi, frames[tree]), packLeftOrFirstCount(first, child.count));
  if (count == 1u) atomicAdd(counters.leafCount, 1u);
}

// Halvings that take n primitives down to one: ceil(log2(n)).
uint halvingsToOne(uint n) { return n <= 1u ? 0u : uint(findMSB(n - 1u)) + 1u; }

// True when a node at `level` may split into children whose larger side holds `larger`
// primitives: halving from there on still ends every leaf within params.maxDepth levels
// (HMB_BVH_MAX_DEPTH). A median split always may, where its node did (ceil(n / 2) needs one
// halving fewer).
bool keepsDepthBound(uint level, uint larger) { return level + 1u + halvingsToOne(larger) <= params.maxDepth; }

#endif
