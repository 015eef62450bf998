#version 450
// A deforming mesh's trace triangles after its vertices moved (kernels/deform/): each leaf
// entry of its tree (a range of the leaves' order) has its three vertices read again from the
// scene's vertex buffer (the vertex indices ride in w), and its triangle's new box for the
// refit, at its primitive's index.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "bvh_build_layout.h"
#include "triangle_box.glsl"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_BVH_BUILD_GROUP) in;

layout(std430, binding = HMB_DEFORMED_LEAVES_BINDING_VERTICES) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_DEFORMED_LEAVES_BINDING_PRIMITIVES) readonly buffer Primitives { uint primitives[]; };
layout(std430, binding = HMB_DEFORMED_LEAVES_BINDING_LEAF_TRIANGLES) buffer LeafTriangles { vec4 leafTriangles[]; };
layout(std430, binding = HMB_DEFORMED_LEAVES_BINDING_BOXES) writeonly buffer Boxes { BvhBox boxes[]; };
layout(push_constant) uniform Params { uvec2 entries; };  // first, count

void main() {
  const uint i = linearInvocationIndex(HMB_BVH_BUILD_GROUP);
  if (i >= entries.y) return;
  const uint e = entries.x + i;
  vec3 corner[3];
  for (uint c = 0; c < 3; ++c) {
    const float index = leafTriangles[3u * e + c].w;
    corner[c] = vertices[floatBitsToUint(index)].position.xyz;
    leafTriangles[3u * e + c] = vec4(corner[c], index);
  }
  boxes[primitives[e]] = triangleBox(corner[0], corner[1], corner[2]);
}
