#version 450
// The linear builder's last pass (linear_bvh_layout.h): a lane per node packs it where traversal
// reads it, in the tree's frame (each lane makes it from the root's box, the first writes it):
// the root at 0, the children of interior node i at 2 i + 1 (left) and 2 i + 2, a leaf's one
// primitive at its place in the sorted order. An empty tree is its root alone, with an empty box.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "linear_bvh_layout.h"
#include "packed_node.glsl"

layout(local_size_x = HMB_LINEAR_BVH_GROUP) in;
layout(std430, binding = HMB_LINEAR_PACK_BINDING_LINKS) readonly buffer Links { LinearBvhLink links[]; };
layout(std430, binding = HMB_LINEAR_PACK_BINDING_EXACT) readonly buffer Exact { BvhBox exact[]; };
layout(std430, binding = HMB_LINEAR_PACK_BINDING_FRAMES) writeonly buffer Frames { BvhFrame frames[]; };
layout(std430, binding = HMB_LINEAR_PACK_BINDING_PACKED_NODES) writeonly buffer PackedNodes { uvec4 packedNodes[]; };
layout(push_constant) uniform Params { LinearBvhParams params; };

void main() {
  const uint node = linearInvocationIndex(HMB_LINEAR_BVH_GROUP), n = params.primitiveCount;
  if (n == 0u) {
    if (node != 0u) return;
    frames[0] = frameOf(vec3(1.0), vec3(0.0));
    packedNodes[0] = uvec4(uvec3(HMB_BVH_QUANTUM_MAX), packLeftOrFirstCount(0u, 0u));
    return;
  }
  if (node >= 2u * n - 1u) return;
  const BvhFrame frame = frameOf(exact[0].min.xyz, exact[0].max.xyz);  // the root, Karras-named 0
  if (node == 0u) frames[0] = frame;
  uint at = 0u;
  if (node != 0u) {
    const uint parent = links[node].parent;
    at = 2u * parent + (links[parent].right == node ? 2u : 1u);
  }
  const bool leaf = node >= n - 1u;
  const uint word = leaf ? packLeftOrFirstCount(node - (n - 1u), 1u) : packLeftOrFirstCount(2u * node + 1u, 0u);
  packedNodes[at] = uvec4(packBox(exact[node].min.xyz, exact[node].max.xyz, frame), word);
}
