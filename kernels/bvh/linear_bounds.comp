#version 450
// The linear builder's third pass (linear_bvh_layout.h): a lane per leaf writes its primitive's
// box and climbs. At each node the first of its two lanes to arrive stops, the second bounds
// it from both children and climbs on, so every node is bounded once, after its children, and
// no lane waits for another.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "linear_bvh_layout.h"

layout(local_size_x = HMB_LINEAR_BVH_GROUP) in;
layout(std430, binding = HMB_LINEAR_BOUNDS_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
layout(std430, binding = HMB_LINEAR_BOUNDS_BINDING_PRIMITIVES) readonly buffer Primitives { uint primitives[]; };
// A lane reads the box another lane wrote before the atomic that let it on.
layout(std430, binding = HMB_LINEAR_BOUNDS_BINDING_LINKS) coherent buffer Links { LinearBvhLink links[]; };
layout(std430, binding = HMB_LINEAR_BOUNDS_BINDING_EXACT) coherent buffer Exact { BvhBox exact[]; };
layout(push_constant) uniform Params { LinearBvhParams params; };

// Lavapipe 22.3 returned wrong counts from atomics to lanes of a vector some of whose lanes had
// stopped climbing (a node bounded by no lane): on such a driver every lane takes every round,
// its atomic adding 0 once it stopped (DeviceProfile::uniformAtomicRounds). Elsewhere a lane
// stops where it stops, and a warp leaves the loop with its last climbing lane.
layout(constant_id = HMB_SPEC_LINEAR_UNIFORM_ROUNDS) const bool kUniformRounds = false;

void main() {
  const uint leaf = linearInvocationIndex(HMB_LINEAR_BVH_GROUP), n = params.primitiveCount;
  bool climbing = leaf < n;
  uint node = climbing ? n - 1u + leaf : 0u;  // a tree of one primitive: its leaf is the root, node 0
  BvhBox box;
  if (climbing) {
    box = boxes[primitives[leaf]];
    exact[node] = box;
  }
  uint parent = climbing && n > 1u ? links[node].parent : HMB_LINEAR_BVH_NONE;
  climbing = parent != HMB_LINEAR_BVH_NONE;
  // The first lane to reach a node stops there (the other child's lane bounds it); the second
  // bounds it and climbs on. No node lies deeper than HMB_BVH_MAX_DEPTH.
  for (uint round = 0u; round < HMB_BVH_MAX_DEPTH && (kUniformRounds || climbing); ++round) {
    memoryBarrierBuffer();
    const uint arrived = atomicAdd(links[climbing ? parent : node].visits, climbing ? 1u : 0u);
    memoryBarrierBuffer();
    const bool second = climbing && arrived != 0u;
    if (second) {
      const BvhBox left = exact[links[parent].left], right = exact[links[parent].right];
      box.min = min(left.min, right.min);
      box.max = max(left.max, right.max);
      node = parent;
      exact[node] = box;
      parent = links[node].parent;
    }
    climbing = second && parent != HMB_LINEAR_BVH_NONE;
  }
}
