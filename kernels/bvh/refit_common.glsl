// What the refit kernels share: their bindings (each kernel declares the ones it uses with
// these macros) and which nodes a refit leaves alone.
#ifndef HMB_KERNELS_BVH_REFIT_COMMON_GLSL
#define HMB_KERNELS_BVH_REFIT_COMMON_GLSL

#include "bvh_build_layout.h"
#include "packed_node.glsl"
#include "../shared/indexing.glsl"

#define REFIT_BOXES layout(std430, binding = HMB_REFIT_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
#define REFIT_ROOTS layout(std430, binding = HMB_REFIT_BINDING_ROOTS) readonly buffer Roots { uvec2 roots[]; };
#define REFIT_PRIMITIVES \
  layout(std430, binding = HMB_REFIT_BINDING_PRIMITIVES) readonly buffer Primitives { uint primitives[]; };
#define REFIT_PACKED_NODES \
  layout(std430, binding = HMB_REFIT_BINDING_PACKED_NODES) buffer PackedNodes { uvec4 packedNodes[]; };
#define REFIT_FRAMES layout(std430, binding = HMB_REFIT_BINDING_FRAMES) buffer Frames { BvhFrame frames[]; };
#define REFIT_EXACT layout(std430, binding = HMB_REFIT_BINDING_EXACT) buffer Exact { BvhBox exact[]; };
#define REFIT_PARENTS layout(std430, binding = HMB_REFIT_BINDING_PARENTS) buffer Parents { uint parents[]; };
#define REFIT_PLACES layout(std430, binding = HMB_REFIT_BINDING_PLACES) buffer Places { uvec2 places[]; };
#define REFIT_ORDER layout(std430, binding = HMB_REFIT_BINDING_ORDER) readonly buffer Order { uint order[]; };

layout(push_constant) uniform Params { BvhRefitParams params; };
layout(local_size_x = HMB_REFIT_GROUP) in;

// The root of an empty tree has no children and no box to refit, whatever its index word says.
#define IS_EMPTY_ROOT(node) ((node) < params.treeCount && roots[node].y == 0u)

#endif
