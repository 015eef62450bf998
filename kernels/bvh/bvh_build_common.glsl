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

#endif
