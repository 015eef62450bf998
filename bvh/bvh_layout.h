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

HMB_GPU_BEGIN

// 32 bytes. Bounds are scalars, not vec3: glsl_cpp.h shares no vec3 (its std430 alignment of
// 16 differs from glm's 4). All eight members are 4-byte scalars at offsets 0..28, so both
// languages agree; a kernel wanting 128-bit loads may view the same buffer as uvec4[2 * n]
// (x, y, z = min, w = leftOrFirst; then max, count) with uintBitsToFloat.
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

// Closest hit of one ray. The hit point is (1 - u - v) * v0 + u * v1 + v * v2.
struct BvhHit {
  float t;        // ray parameter: origin + t * direction
  float u;        // barycentric weight of the triangle's second vertex
  float v;        // barycentric weight of the third vertex
  uint triangle;  // HMB_NO_HIT when nothing was hit
  uint objectId;  // object of the hit triangle (HMB_NO_HIT when nothing was hit)
  uint instance;  // two-level traces: the instance hit (HMB_NO_HIT when nothing was hit)
  uint pad1;
  uint pad2;
};

HMB_GPU_END

HMB_CHECK_SIZE(BvhNode, 32)
HMB_CHECK_SIZE(BvhHit, 32)

#endif
