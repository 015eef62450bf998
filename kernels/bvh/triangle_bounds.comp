#version 450
// The box of every triangle: what the builder bins and partitions (triangle_box.glsl).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "bvh_build_layout.h"
#include "triangle_box.glsl"
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
  boxes[i] = triangleBox(positions[t.x].xyz, positions[t.y].xyz, positions[t.z].xyz);
}
