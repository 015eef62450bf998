#version 450
// The box of every triangle: what the builder bins and partitions. A triangle with a
// non-finite vertex gets an empty box, so it can never be hit and never widens a node.
#extension GL_GOOGLE_include_directive : require
#include "bvh_build_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_BVH_BUILD_GROUP) in;

layout(std430, binding = HMB_TRIANGLE_BOUNDS_BINDING_POSITIONS) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = HMB_TRIANGLE_BOUNDS_BINDING_TRIANGLES) readonly buffer Triangles { uvec4 triangles[]; };
layout(std430, binding = HMB_TRIANGLE_BOUNDS_BINDING_BOXES) writeonly buffer Boxes { BvhBox boxes[]; };
layout(push_constant) uniform Params { uint triangleCount; };

void main() {
  const uint i = linearInvocationIndex(HMB_BVH_BUILD_GROUP);
  if (i >= triangleCount) return;
  const uvec4 t = triangles[i];
  const vec3 a = positions[t.x].xyz, b = positions[t.y].xyz, c = positions[t.z].xyz;
  vec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
  const vec3 all3 = a + b + c;  // NaN or inf when any vertex is (or when they overflow)
  const bool finite = !any(isnan(all3)) && !any(isinf(all3)) && !any(isinf(a)) && !any(isinf(b)) && !any(isinf(c));
  if (!finite) {
    lo = vec3(uintBitsToFloat(0x7f800000u));
    hi = -lo;
  }
  boxes[i].min = vec4(lo, 0.0);
  boxes[i].max = vec4(hi, 0.0);
}
