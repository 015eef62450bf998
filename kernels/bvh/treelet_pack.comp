#version 450
// The treelet builder's last pass (treelet_build_layout.h): a lane per node of the binary tree
// walks up to its root and finds, from the subtrees' sizes to its left, where it goes in the
// output: tree r's root at node r, an interior node's children as a pair, after them its left
// child's nodes, then its right child's; and where its primitives go (the tree's range in the
// order of its leaves). A node below one output as a leaf is not output itself, but a leaf
// still places its primitive. Each node is packed in its tree's frame (the root's box), as the
// binned builder packs them. Lanes past the nodes write the root of each empty tree.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "treelet_common.glsl"
#include "packed_node.glsl"

layout(local_size_x = HMB_TREELET_GROUP) in;
layout(std430, binding = HMB_TREELET_BINDING_NODES) readonly buffer Nodes { TreeletNode nodes[]; };
layout(std430, binding = HMB_TREELET_BINDING_TREES) readonly buffer Trees { TreeletTree trees[]; };
layout(std430, binding = HMB_TREELET_BINDING_VALUES) readonly buffer Values { uint values[]; };
layout(std430, binding = HMB_TREELET_BINDING_COUNTERS) buffer Counters { BvhBuildCounters counters; };
layout(std430, binding = HMB_TREELET_BINDING_EXACT_NODES) writeonly buffer ExactNodes { BvhNode exactNodes[]; };
layout(std430, binding = HMB_TREELET_BINDING_PACKED_NODES) writeonly buffer PackedNodes { uvec4 packedNodes[]; };
layout(std430, binding = HMB_TREELET_BINDING_FRAMES) writeonly buffer Frames { BvhFrame frames[]; };
layout(std430, binding = HMB_TREELET_BINDING_PRIMITIVES) writeonly buffer Primitives { uint primitives[]; };
layout(push_constant) uniform Params { TreeletBuildParams params; };

void write(uint at, vec3 lo, vec3 hi, BvhFrame frame, uint leftOrFirst, uint count) {
  packedNodes[at] = uvec4(packBox(lo, hi, frame), packLeftOrFirstCount(leftOrFirst, count));
  BvhNode exact;
  exact.minX = lo.x;
  exact.minY = lo.y;
  exact.minZ = lo.z;
  exact.leftOrFirst = leftOrFirst;
  exact.maxX = hi.x;
  exact.maxY = hi.y;
  exact.maxZ = hi.z;
  exact.count = count;
  exactNodes[at] = exact;
}

void main() {
  const uint node = linearInvocationIndex(HMB_TREELET_GROUP), n = params.primitiveCount;
  if (node >= 2u * n) {
    // An empty tree: a root without children and an empty box, which no ray enters.
    const uint tree = node - 2u * n;
    if (tree >= params.treeCount || trees[tree].count != 0u) return;
    const vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
    const BvhFrame frame = frameOf(lo, hi);
    frames[tree] = frame;
    write(tree, lo, hi, frame, trees[tree].first, 0u);
    return;
  }
  if (nodes[node].count == 0u) return;  // no interior node at this place, or no tree
  const bool primitive = node >= n;

  // Up to the root: the output nodes and primitives left of the way down, whether a node above
  // is output as a leaf, and the node's depth.
  uint nodesLeft = 0u, primitivesLeft = 0u, depth = 1u, step = 0u;
  bool hidden = false, isRight = false;
  uint at = node;
  for (uint round = 0u; round < HMB_TREELET_MAX_HEIGHT; ++round) {
    const uint parent = nodes[at].parent;
    if (parent == HMB_TREELET_NONE) break;
    const uint left = nodes[parent].left;
    const bool right = left != at;
    const uint thisStep = 2u + (right ? nodes[left].below : 0u);
    if (at == node) {
      isRight = right;
      step = thisStep;
    }
    nodesLeft += thisStep;
    primitivesLeft += right ? nodes[left].count : 0u;
    hidden = hidden || nodes[parent].below == 0u;
    if (hidden && !primitive) return;
    ++depth;
    at = parent;
  }
  const uint tree = nodes[at].tree;
  const uint first = trees[tree].first + primitivesLeft;
  if (primitive) primitives[first] = values[node - n];
  if (hidden) return;

  const vec3 lo = nodes[node].lo.xyz, hi = nodes[node].hi.xyz;
  const BvhFrame frame = frameOf(nodes[at].lo.xyz, nodes[at].hi.xyz);
  const uint base = trees[tree].nodeBase + nodesLeft;  // where the node's children go
  uint place = tree;
  if (node != at) {
    place = base - step + (isRight ? 1u : 0u);
  } else {
    frames[tree] = frame;
  }
  if (nodes[node].below == 0u) {
    write(place, lo, hi, frame, first, nodes[node].count);
    atomicAdd(counters.leafCount, 1u);
  } else {
    write(place, lo, hi, frame, base, 0u);
  }
  atomicMax(counters.levels, depth);
}
