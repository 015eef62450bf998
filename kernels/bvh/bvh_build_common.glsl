// What the BVH build kernels share: their bindings, and how a box yields the centroid it is
// binned and partitioned by.
#ifndef HMB_KERNELS_BVH_BVH_BUILD_COMMON_GLSL
#define HMB_KERNELS_BVH_BVH_BUILD_COMMON_GLSL

#include "bvh_build_layout.h"
#include "packed_node.glsl"

layout(std430, binding = HMB_BUILD_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
layout(std430, binding = HMB_BUILD_BINDING_ROOTS) readonly buffer Roots { uvec2 roots[]; };
layout(std430, binding = HMB_BUILD_BINDING_PRIMITIVES) buffer Primitives { uint primitives[]; };
layout(std430, binding = HMB_BUILD_BINDING_NODES) buffer Nodes { BvhNode nodes[]; };
layout(std430, binding = HMB_BUILD_BINDING_LINKS) buffer Links { uint links[]; };
layout(std430, binding = HMB_BUILD_BINDING_TASKS) buffer Tasks {
  BvhBuildCounters counters;
  BvhBuildTask tasks[];
};
layout(std430, binding = HMB_BUILD_BINDING_PACKED_NODES) buffer PackedNodes { uvec4 packedNodes[]; };
layout(std430, binding = HMB_BUILD_BINDING_FRAMES) buffer Frames { BvhFrame frames[]; };
layout(push_constant) uniform Params { BvhBuildParams params; };

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
// its tree's frame; a child of one primitive is a leaf at once (the others get their index word
// when they are split or made leaves).
void writeChild(uint index, uint first, uint count, uint tree, vec3 lo, vec3 hi) {
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
  packedNodes[index] = uvec4(packBox(lo, hi, frames[tree]), packLeftOrFirstCount(first, child.count));
  if (count == 1u) atomicAdd(counters.leafCount, 1u);
}

// The links of one direction octant when `node` splits along `axis` into children left and
// left + 1: the child on the ray's side of the split first, the other after it, and after that
// wherever the node led before.
void linkChildren(uint node, uint left, uint axis, uint octant) {
  const uint rightFirst = (octant >> axis) & 1u;
  const uint escape = links[node * HMB_BVH_OCTANTS + octant] & HMB_BVH_LINK_NEXT_MASK;
  links[(left + rightFirst) * HMB_BVH_OCTANTS + octant] = left + 1u - rightFirst;
  links[(left + 1u - rightFirst) * HMB_BVH_OCTANTS + octant] = escape;
  links[node * HMB_BVH_OCTANTS + octant] = escape | (rightFirst != 0u ? HMB_BVH_LINK_RIGHT_FIRST : 0u);
}

#endif
