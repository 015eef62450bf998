#version 450
// A kept tree with a few primitives inserted (bvh_build_layout.h, HMB_BVH_MAX_INSERTED), one
// workgroup: its lanes restore the kept tree's exact nodes as they were built; one lane inserts
// the order's places past the kept ones in turn, each going down from the root, the nodes it
// passes growing to take it in, to the child whose area it enlarges least (the smaller on a
// tie), down to a leaf, which moves to a new pair of nodes beside the inserted primitive's leaf
// and becomes their parent; then every node is packed again in the frame of the new root box
// (tree 0's). Stopping higher, where a new node costs less surface area than going on
// (Goldsmith and Salmon's greedy insertion), traced bistro's reveal no faster (within the
// spread of alternated runs: bench/results/top-level-insertion/). The kept tree's nodes are
// packed on each insertion because the root's box, and so the frame, moves with the inserted
// boxes. Each insertion deepens the tree by at most a level: the host keeps the kept tree's
// depth bound and the insertions within HMB_BVH_MAX_DEPTH.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
// The lanes read the nodes and the node count that others wrote before a barrier.
#define HMB_BVH_BUILD_COHERENT coherent
#include "bvh_build_common.glsl"

layout(local_size_x = HMB_BVH_PACK_GROUP) in;
layout(std430, binding = HMB_BUILD_BINDING_KEPT_NODES) readonly buffer KeptNodes { BvhNode keptNodes[]; };

vec3 lowerOf(BvhNode n) { return vec3(n.minX, n.minY, n.minZ); }
vec3 upperOf(BvhNode n) { return vec3(n.maxX, n.maxY, n.maxZ); }

void setBox(inout BvhNode n, vec3 lo, vec3 hi) {
  n.minX = lo.x, n.minY = lo.y, n.minZ = lo.z;
  n.maxX = hi.x, n.maxY = hi.y, n.maxZ = hi.z;
}

// What the node's box grows by, in area, when it takes in lo..hi; an empty box grows to it.
float enlargement(BvhNode n, vec3 lo, vec3 hi) {
  const vec3 nodeLo = lowerOf(n), nodeHi = upperOf(n);
  return surfaceArea(min(nodeLo, lo), max(nodeHi, hi)) - surfaceArea(nodeLo, nodeHi);
}

void main() {
  const uint lane = gl_LocalInvocationID.x;
  const uint kept = roots[0].y;
  const uint keptEnd = 2u * kept + params.treeCount;  // past what a build of the kept may allocate
  for (uint node = lane; node < keptEnd; node += HMB_BVH_PACK_GROUP) nodes[node] = keptNodes[node];
  memoryBarrierBuffer();
  barrier();

  if (lane == 0u) {
    uint next = keptEnd;
    for (uint place = kept; place < params.primitiveCount; ++place) {
      const BvhBox box = boxAt(primitives[place]);
      // An empty box (a primitive with nothing to hit) grows nothing, and still gets its leaf.
      const bool empty = !all(lessThanEqual(box.min.xyz, box.max.xyz));
      const vec3 lo = empty ? vec3(uintBitsToFloat(0x7f800000u)) : box.min.xyz, hi = empty ? -lo : box.max.xyz;
      uint node = HMB_BVH_ROOT;
      BvhNode at = nodes[node];
      while (at.count == 0u) {
        setBox(at, min(lowerOf(at), lo), max(upperOf(at), hi));
        nodes[node] = at;
        const BvhNode left = nodes[at.leftOrFirst], right = nodes[at.leftOrFirst + 1u];
        const float growLeft = enlargement(left, lo, hi), growRight = enlargement(right, lo, hi);
        const bool toRight = growRight < growLeft || (growRight == growLeft && surfaceArea(lowerOf(right), upperOf(right)) <
                                                                                 surfaceArea(lowerOf(left), upperOf(left)));
        node = at.leftOrFirst + (toRight ? 1u : 0u);
        at = toRight ? right : left;
      }
      BvhNode leaf;
      setBox(leaf, lo, hi);
      leaf.leftOrFirst = place;
      leaf.count = 1u;
      nodes[next] = at;
      nodes[next + 1u] = leaf;
      setBox(at, min(lowerOf(at), lo), max(upperOf(at), hi));
      at.leftOrFirst = next;
      at.count = 0u;
      nodes[node] = at;
      next += 2u;
    }
    counters.nodeCount = next;
  }
  memoryBarrierBuffer();
  barrier();

  const BvhNode root = nodes[HMB_BVH_ROOT];
  const BvhFrame frame = frameOf(lowerOf(root), upperOf(root));
  if (lane == 0u) frames[0] = frame;
  const uint count = counters.nodeCount;
  for (uint node = lane; node < count; node += HMB_BVH_PACK_GROUP) {
    const BvhNode n = nodes[node];
    packedNodes[node] = uvec4(packBox(lowerOf(n), upperOf(n), frame), packLeftOrFirstCount(n.leftOrFirst, n.count));
  }
}
