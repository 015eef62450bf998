// What the refit kernels share: their bindings, and which nodes a refit leaves alone.
#ifndef HMB_KERNELS_BVH_REFIT_COMMON_GLSL
#define HMB_KERNELS_BVH_REFIT_COMMON_GLSL

#include "bvh_build_layout.h"
#include "packed_node.glsl"
#include "../shared/indexing.glsl"

layout(std430, binding = HMB_REFIT_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
layout(std430, binding = HMB_REFIT_BINDING_ROOTS) readonly buffer Roots { uvec2 roots[]; };
layout(std430, binding = HMB_REFIT_BINDING_PRIMITIVES) readonly buffer Primitives { uint primitives[]; };
layout(std430, binding = HMB_REFIT_BINDING_PACKED_NODES) buffer PackedNodes { uvec4 packedNodes[]; };
layout(std430, binding = HMB_REFIT_BINDING_FRAMES) buffer Frames { BvhFrame frames[]; };
layout(std430, binding = HMB_REFIT_BINDING_EXACT) buffer Exact { BvhBox exact[]; };
layout(std430, binding = HMB_REFIT_BINDING_PARENTS) buffer Parents { uint parents[]; };
layout(std430, binding = HMB_REFIT_BINDING_DEPTHS) buffer Depths { uint depths[]; };
layout(push_constant) uniform Params { BvhRefitParams params; };

layout(local_size_x = HMB_REFIT_GROUP) in;

// The root of an empty tree has no children and no box to refit, whatever its index word says.
bool isEmptyRoot(uint node) { return node < params.treeCount && roots[node].y == 0u; }
// A node whose index word is a leaf's (a tree of one primitive is a leaf root).
bool isLeaf(uint node) { return packedCount(packedNodes[node]) != 0u; }

#endif
