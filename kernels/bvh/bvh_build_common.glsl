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
layout(std430, binding = HMB_BUILD_BINDING_NODES) buffer Nodes { BvhNode nodes[]; };
// A node's 8 link words (one per direction octant) as two uvec4: octants 0-3, then 4-7.
layout(std430, binding = HMB_BUILD_BINDING_LINKS) buffer Links { uvec4 linkQuads[]; };
layout(std430, binding = HMB_BUILD_BINDING_TASKS) buffer Tasks {
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
// wherever the node led before. One word each (build_level gives each octant its own lane).
void linkChildren(uint node, uint left, uint axis, uint octant) {
  const uint rightFirst = (octant >> axis) & 1u;
  const uint quad = octant >> 2u, word = octant & 3u;
  const uint escape = linkQuads[node * 2u + quad][word] & HMB_BVH_LINK_NEXT_MASK;
  linkQuads[(left + rightFirst) * 2u + quad][word] = left + 1u - rightFirst;
  linkQuads[(left + 1u - rightFirst) * 2u + quad][word] = escape;
  linkQuads[node * 2u + quad][word] = escape | (rightFirst != 0u ? HMB_BVH_LINK_RIGHT_FIRST : 0u);
}

// linkChildren for all 8 octants at once, for one invocation that splits a node alone
// (build_small_tasks): two loads and six stores of four words, where a word at a time is 32
// accesses (on lavapipe each a loop over the lanes).
void linkChildrenAllOctants(uint node, uint left, uint axis) {
  for (uint quad = 0u; quad < 2u; ++quad) {
    const uvec4 octants = uvec4(0u, 1u, 2u, 3u) + 4u * quad;
    const bvec4 rightFirst = notEqual((octants >> axis) & 1u, uvec4(0u));
    const uvec4 escape = linkQuads[node * 2u + quad] & HMB_BVH_LINK_NEXT_MASK;
    linkQuads[left * 2u + quad] = mix(uvec4(left + 1u), escape, rightFirst);
    linkQuads[(left + 1u) * 2u + quad] = mix(escape, uvec4(left), rightFirst);
    linkQuads[node * 2u + quad] = escape | mix(uvec4(0u), uvec4(HMB_BVH_LINK_RIGHT_FIRST), rightFirst);
  }
}

#endif
