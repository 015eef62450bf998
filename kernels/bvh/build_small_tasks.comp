#version 450
// The subtrees of the small tasks build_level set aside (at most HMB_BVH_SMALL_TASK primitives
// each), one invocation per task, after the levels: top-down, each node split where an exact
// SAH sweep over its primitives sorted by centroid along each axis is cheapest (the cost that
// build_level estimates with bins), or made a leaf when it may be one and that costs no more.
// Nodes, packed nodes and links are written as build_level writes them, so traversal cannot
// tell the two apart; the subtree's primitives end in their final order in the first half of
// the primitive array.
#extension GL_GOOGLE_include_directive : require
#include "bvh_build_common.glsl"
#include "../shared/indexing.glsl"

#define SMALL HMB_BVH_SMALL_TASK

layout(local_size_x = HMB_BVH_SMALL_TASK_GROUP) in;

// The task's primitives, reordered as its nodes split them.
uint order[SMALL];
// The node being split: its primitives' boxes and centroids (by position in its range), the
// positions sorted by centroid along one axis (centroid, position as bits: one access moves
// both, and on lavapipe each access at per-lane indices is a loop over the lanes), the best
// axis's sorted positions, and the right sides' areas of the sweep.
vec3 boxLo[SMALL], boxHi[SMALL], centre[SMALL];
vec2 sorted[SMALL];
uint best[SMALL];
uint reordered[SMALL];
float rightArea[SMALL];

// Node, first position in `order`, count, level: what is left to split.
uvec4 stack[SMALL];

void main() {
  const uint index = linearInvocationIndex(HMB_BVH_SMALL_TASK_GROUP);
  if (index >= counters.smallTaskCount) return;
  const BvhBuildTask task = tasks[2u * params.taskCapacity + index];
  const uint inBase = uint(task.centroidMax.w) * params.primitiveCount;
  for (uint k = 0; k < task.count; ++k) order[k] = primitives[inBase + task.first + k];

  uint depth = 1u;
  stack[0] = uvec4(task.node, 0u, task.count, uint(task.centroidMin.w));
  while (depth > 0u) {
    const uvec4 entry = stack[--depth];
    const uint node = entry.x, first = entry.y, count = entry.z, level = entry.w;
    const BvhNode bounds = nodes[node];
    const float nodeArea = surfaceArea(vec3(bounds.minX, bounds.minY, bounds.minZ), vec3(bounds.maxX, bounds.maxY, bounds.maxZ));

    for (uint k = 0; k < count; ++k) {
      const BvhBox box = boxes[order[first + k]];
      boxLo[k] = box.min.xyz;
      boxHi[k] = box.max.xyz;
      centre[k] = centroidOf(box);
      best[k] = k;  // kept if no split has a finite cost: the range is halved as it is
    }
    // The cheapest split over the three axes: sort by centroid (insertion sort, stable, so that
    // equal centroids keep their order), sweep right to left for the right sides' areas, then
    // left to right costing each split as build_level does.
    float bestCost = uintBitsToFloat(0x7f800000u);
    uint bestAxis = 0u, bestLeft = 0u;
    for (uint axis = 0; axis < 3; ++axis) {
      for (uint k = 0; k < count; ++k) {
        const float c = centre[k][axis];
        uint at = k;
        while (at > 0u) {
          const vec2 before = sorted[at - 1u];
          if (!(before.x > c)) break;
          sorted[at] = before;
          --at;
        }
        sorted[at] = vec2(c, uintBitsToFloat(k));
      }
      vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
      for (uint k = count - 1u; k > 0u; --k) {
        const uint at = floatBitsToUint(sorted[k].y);
        lo = min(lo, boxLo[at]);
        hi = max(hi, boxHi[at]);
        rightArea[k] = surfaceArea(lo, hi);
      }
      lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
      bool improved = false;
      for (uint left = 1u; left < count; ++left) {
        const uint at = floatBitsToUint(sorted[left - 1u].y);
        lo = min(lo, boxLo[at]);
        hi = max(hi, boxHi[at]);
        // A node with no area (all primitives on a line or a point) weighs children equally.
        const float leftShare = nodeArea > 0.0 ? surfaceArea(lo, hi) / nodeArea : 1.0;
        const float rightShare = nodeArea > 0.0 ? rightArea[left] / nodeArea : 1.0;
        const float cost = 1.0 + leftShare * float(left) + rightShare * float(count - left);
        if (cost < bestCost) bestCost = cost, bestAxis = axis, bestLeft = left, improved = true;
      }
      if (improved)
        for (uint k = 0; k < count; ++k) best[k] = floatBitsToUint(sorted[k].y);
    }
    if (bestLeft == 0u) bestLeft = count / 2u;

    if (count <= params.maxLeaf && float(count) <= bestCost) {
      nodes[node].leftOrFirst = task.first + first;
      nodes[node].count = count;
      packedNodes[node].w = packLeftOrFirstCount(task.first + first, count);
      atomicAdd(counters.leafCount, 1u);
      continue;
    }
    for (uint k = 0; k < count; ++k) reordered[k] = order[first + best[k]];
    for (uint k = 0; k < count; ++k) order[first + k] = reordered[k];
    const uint left = atomicAdd(counters.nodeCount, 2u);
    atomicMax(counters.levels, level + 2u);
    linkChildrenAllOctants(node, left, bestAxis);
    nodes[node].leftOrFirst = left;
    nodes[node].count = 0u;
    packedNodes[node].w = packLeftOrFirstCount(left, 0u);
    for (uint side = 0; side < 2; ++side) {
      const uint childFirst = side == 0u ? first : first + bestLeft;
      const uint childCount = side == 0u ? bestLeft : count - bestLeft;
      vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
      for (uint k = 0; k < childCount; ++k) {
        const BvhBox box = boxes[order[childFirst + k]];
        lo = min(lo, box.min.xyz);
        hi = max(hi, box.max.xyz);
      }
      writeChild(left + side, task.first + childFirst, childCount, task.tree, lo, hi);
      if (childCount > 1u) stack[depth++] = uvec4(left + side, childFirst, childCount, level + 1u);
    }
  }
  for (uint k = 0; k < task.count; ++k) primitives[task.first + k] = order[k];
}
