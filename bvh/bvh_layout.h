// The BVH as kernels see it: binary nodes and the hit record of a closest-hit query, laid out
// identically for GLSL (std430) and C++.
#ifndef HMB_BVH_BVH_LAYOUT_H
#define HMB_BVH_BVH_LAYOUT_H

#include "../kernels/shared/glsl_cpp.h"

// A node with count == 0 is interior: its children are nodes leftOrFirst and leftOrFirst + 1.
// A node with count > 0 is a leaf: it holds primitives primitiveIndices[leftOrFirst ..
// leftOrFirst + count). Node 0 is the root.
#define HMB_BVH_ROOT 0u

// Hit record value of `triangle` (and `objectId`) when the ray hit nothing.
#define HMB_NO_HIT 0xffffffffu

// Value of the "ignore this object id" query option that ignores nothing.
#define HMB_IGNORE_NONE 0xffffffffu

// Packed nodes (what traversal reads): each bound is a 16-bit step count in its tree's frame,
// and the last word holds leftOrFirst above the count. A leaf holds at most
// HMB_BVH_PACKED_MAX_COUNT primitives, and node and primitive indices stay below
// HMB_BVH_PACKED_INDEX_LIMIT.
#define HMB_BVH_QUANTUM_MAX 65535u
#define HMB_BVH_PACKED_COUNT_BITS 3u
#define HMB_BVH_PACKED_MAX_COUNT 7u
#define HMB_BVH_PACKED_INDEX_LIMIT 0x20000000u

HMB_GPU_BEGIN

// A node with exact bounds, 32 bytes: the host's trees and the device builder's working copy
// (traversal reads BvhPackedNode). Bounds are scalars, not vec3: glsl_cpp.h shares no vec3
// (its std430 alignment of 16 differs from glm's 4). All eight members are 4-byte scalars at
// offsets 0..28, so both languages agree.
struct BvhNode {
  float minX;
  float minY;
  float minZ;
  uint leftOrFirst;  // interior: left child node; leaf: first entry in the primitive-index array
  float maxX;
  float maxY;
  float maxZ;
  uint count;        // 0: interior; > 0: number of primitives in the leaf
};

// A node as traversal reads it, 16 bytes: x, y, z hold the box's lower step count in bits
// 0-15 and its upper one in bits 16-31 (bound = frame origin + steps * frame step, see
// kernels/bvh/packed_node.glsl); w holds leftOrFirst << 3 | count. An empty box (a tree or a
// leaf with nothing to hit) is lower 65535, upper 0 on every axis: never entered.
struct BvhPackedNode {
  uint x;
  uint y;
  uint z;
  uint leftOrFirstCount;
};

// The frame a tree's packed bounds count steps in: its root box, 65535 steps across each axis.
struct BvhFrame {
  vec4 origin;  // xyz: the root box's lower corner (w unused)
  vec4 step;    // xyz: the length of one step (w unused)
};

// Closest hit of one ray. The hit point is (1 - u - v) * v0 + u * v1 + v * v2.
struct BvhHit {
  float t;        // ray parameter: origin + t * direction
  float u;        // barycentric weight of the triangle's second vertex
  float v;        // barycentric weight of the third vertex
  uint triangle;  // HMB_NO_HIT when nothing was hit
  uint objectId;  // object of the hit triangle (HMB_NO_HIT when nothing was hit)
  uint instance;  // two-level traces: the instance hit (HMB_NO_HIT when nothing was hit)
  uint entry;     // device traces: the hit triangle's place in the leaves' order (TraceScene)
  // Device traces: 1 when the driver's loop limit cut the walk short (Mesa 22.3's lavapipe ends
  // every loop of an invocation after 65535 rounds in all), so that the hit may be wrong.
  uint cut;
};

HMB_GPU_END

HMB_CHECK_SIZE(BvhNode, 32)
HMB_CHECK_SIZE(BvhHit, 32)
HMB_CHECK_SIZE(BvhPackedNode, 16)
HMB_CHECK_SIZE(BvhFrame, 32)

#endif
