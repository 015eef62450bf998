#version 450
// The subtrees of the small tasks build_level set aside (at most kSmallTask primitives each:
// bvh_build_layout.h), one invocation per task, after the levels: top-down, each node split at the cheapest
// bin boundary by the surface area heuristic, as build_level does, or made a leaf when it may
// be one and that costs no more, or halved where the depth bound asks (keepsDepthBound). Nodes
// and packed nodes are written as build_level writes them, so traversal cannot tell the two
// apart (or packed after, by pack_deferred_nodes: HMB_SPEC_BVH_PACK_LATER); the subtree's
// primitives end in their final order in the first half of the primitive array.
//
// The bins live in registers: every bin is named by a constant once the loops over bins are
// unrolled, and a primitive updates the bin it falls in by comparing its bin with each. On
// lavapipe every access to an array at per-lane indices (private, shared or global) is a loop
// over the lanes, so bins in an array indexed by the primitive's bin, or an exact sweep over
// primitives sorted in such arrays, cost several times the arithmetic; on a GPU the unrolled
// compares are as cheap as the indexed update.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#extension GL_EXT_control_flow_attributes : require
#include "bvh_build_common.glsl"
#include "../shared/indexing.glsl"

#define BINS HMB_BVH_SMALL_TASK_BINS

layout(local_size_x = HMB_BVH_SMALL_TASK_GROUP) in;
layout(constant_id = HMB_SPEC_BVH_SMALL_TASK) const uint SMALL = HMB_BVH_SMALL_TASK;
layout(constant_id = HMB_SPEC_BVH_PACK_LATER) const bool PACK_LATER = false;

#define kInfinity uintBitsToFloat(0x7f800000u)

// The task's primitives, reordered as its nodes split them, and the scratch of one partition.
uint order[SMALL];
uint reordered[SMALL];
// Node, first position in `order`, count, level: what is left to split, and the bounds of its
// primitives' centroids (found while its parent partitioned them).
uvec4 stack[SMALL];
vec4 stackCentreLo[SMALL], stackCentreHi[SMALL];

uint binOf(float c, float lo, float scale) { return uint(clamp((c - lo) * scale, 0.0, float(BINS - 1))); }

void main() {
  const uint index = linearInvocationIndex(HMB_BVH_SMALL_TASK_GROUP);
  if (index >= counters.smallTaskCount) return;
  const BvhBuildTask task = tasks[2u * params.taskCapacity + index];
  const uint inBase = uint(task.centroidMax.w) * params.primitiveCount;
  for (uint k = 0; k < task.count; ++k) order[k] = primitives[inBase + task.first + k];

  uint depth = 1u;
  stack[0] = uvec4(task.node, 0u, task.count, uint(task.centroidMin.w));
  stackCentreLo[0] = task.centroidMin;
  stackCentreHi[0] = task.centroidMax;
  while (depth > 0u) {
    const uvec4 entry = stack[--depth];
    const uint node = entry.x, first = entry.y, count = entry.z, level = entry.w;
    const vec3 centreLo = stackCentreLo[depth].xyz, centreHi = stackCentreHi[depth].xyz;
    const BvhNode bounds = nodes[node];
    const float nodeArea = surfaceArea(vec3(bounds.minX, bounds.minY, bounds.minZ), vec3(bounds.maxX, bounds.maxY, bounds.maxZ));

    // The bins span the centroids' bounds.
    const vec3 extent = centreHi - centreLo;
    vec3 scale;
    [[unroll]] for (uint a = 0; a < 3; ++a)
      scale[a] = extent[a] > 0.0 && !isinf(extent[a]) ? min(float(BINS) / extent[a], 3.0e38) : 0.0;

    // Per axis, per bin: the count and the merged boxes, as vectors of four bins (bins 0-3,
    // then 4-7) so that no bin is ever named by a run-time index.
    vec4 count0[3], count1[3], loX0[3], loX1[3], loY0[3], loY1[3], loZ0[3], loZ1[3];
    vec4 hiX0[3], hiX1[3], hiY0[3], hiY1[3], hiZ0[3], hiZ1[3];
    [[unroll]] for (int a = 0; a < 3; ++a) {
      count0[a] = count1[a] = vec4(0.0);
      loX0[a] = loX1[a] = loY0[a] = loY1[a] = loZ0[a] = loZ1[a] = vec4(kInfinity);
      hiX0[a] = hiX1[a] = hiY0[a] = hiY1[a] = hiZ0[a] = hiZ1[a] = vec4(-kInfinity);
    }
    for (uint k = 0; k < count; ++k) {
      const BvhBox box = boxAt(order[first + k]);
      const vec3 c = centroidOf(box);
#define BIN_AXIS(a)                                                                        \
      {                                                                                    \
        const uint bin = binOf(c[a], centreLo[a], scale[a]);                               \
        const bvec4 in0 = equal(uvec4(bin), uvec4(0u, 1u, 2u, 3u));                        \
        const bvec4 in1 = equal(uvec4(bin), uvec4(4u, 5u, 6u, 7u));                        \
        count0[a] += vec4(in0);                                                            \
        count1[a] += vec4(in1);                                                            \
        loX0[a] = mix(loX0[a], min(loX0[a], vec4(box.min.x)), in0);                        \
        loX1[a] = mix(loX1[a], min(loX1[a], vec4(box.min.x)), in1);                        \
        loY0[a] = mix(loY0[a], min(loY0[a], vec4(box.min.y)), in0);                        \
        loY1[a] = mix(loY1[a], min(loY1[a], vec4(box.min.y)), in1);                        \
        loZ0[a] = mix(loZ0[a], min(loZ0[a], vec4(box.min.z)), in0);                        \
        loZ1[a] = mix(loZ1[a], min(loZ1[a], vec4(box.min.z)), in1);                        \
        hiX0[a] = mix(hiX0[a], max(hiX0[a], vec4(box.max.x)), in0);                        \
        hiX1[a] = mix(hiX1[a], max(hiX1[a], vec4(box.max.x)), in1);                        \
        hiY0[a] = mix(hiY0[a], max(hiY0[a], vec4(box.max.y)), in0);                        \
        hiY1[a] = mix(hiY1[a], max(hiY1[a], vec4(box.max.y)), in1);                        \
        hiZ0[a] = mix(hiZ0[a], max(hiZ0[a], vec4(box.max.z)), in0);                        \
        hiZ1[a] = mix(hiZ1[a], max(hiZ1[a], vec4(box.max.z)), in1);                        \
      }
      BIN_AXIS(0)
      BIN_AXIS(1)
      BIN_AXIS(2)
#undef BIN_AXIS
    }

    // Each axis's splits "bins 0..s left, s+1.. right", costed as build_level costs them; the
    // cheapest keeps its two sides' boxes, the children's bounds.
    float bestCost = kInfinity;
    uint bestAxis = 0u, bestBin = 0u, bestLeft = 0u;
    vec3 bestLo0 = vec3(0.0), bestHi0 = vec3(0.0), bestLo1 = vec3(0.0), bestHi1 = vec3(0.0);
#define BIN_LO(a, b) ((b) < 4 ? vec3(loX0[a][(b) & 3], loY0[a][(b) & 3], loZ0[a][(b) & 3]) \
                              : vec3(loX1[a][(b) & 3], loY1[a][(b) & 3], loZ1[a][(b) & 3]))
#define BIN_HI(a, b) ((b) < 4 ? vec3(hiX0[a][(b) & 3], hiY0[a][(b) & 3], hiZ0[a][(b) & 3]) \
                              : vec3(hiX1[a][(b) & 3], hiY1[a][(b) & 3], hiZ1[a][(b) & 3]))
#define BIN_COUNT(a, b) ((b) < 4 ? count0[a][(b) & 3] : count1[a][(b) & 3])
#define LEFT_STEP(a, b)                                                                    \
    lo = min(lo, BIN_LO(a, b)), hi = max(hi, BIN_HI(a, b)), n += BIN_COUNT(a, b);          \
    leftLo##b = lo, leftHi##b = hi, leftN##b = n;
#define RIGHT_STEP(a, b, s)                                                                \
    lo = min(lo, BIN_LO(a, b)), hi = max(hi, BIN_HI(a, b)), n += BIN_COUNT(a, b);          \
    if (leftN##s != 0.0 && n != 0.0) {                                                     \
      const float leftShare = nodeArea > 0.0 ? surfaceArea(leftLo##s, leftHi##s) / nodeArea : 1.0; \
      const float rightShare = nodeArea > 0.0 ? surfaceArea(lo, hi) / nodeArea : 1.0;    \
      const float cost = 1.0 + leftShare * leftN##s + rightShare * n;                      \
      if (cost < bestCost) {                                                               \
        bestCost = cost, bestAxis = a, bestBin = s, bestLeft = uint(leftN##s);             \
        bestLo0 = leftLo##s, bestHi0 = leftHi##s, bestLo1 = lo, bestHi1 = hi;              \
      }                                                                                    \
    }
#define SWEEP_AXIS(a)                                                                      \
    if (scale[a] != 0.0) {                                                                 \
      vec3 leftLo0, leftHi0, leftLo1, leftHi1, leftLo2, leftHi2, leftLo3, leftHi3;         \
      vec3 leftLo4, leftHi4, leftLo5, leftHi5, leftLo6, leftHi6, leftLo7, leftHi7;         \
      float leftN0, leftN1, leftN2, leftN3, leftN4, leftN5, leftN6, leftN7;                \
      vec3 lo = vec3(kInfinity), hi = -lo;                                                 \
      float n = 0.0;                                                                       \
      LEFT_STEP(a, 0) LEFT_STEP(a, 1) LEFT_STEP(a, 2) LEFT_STEP(a, 3)                      \
      LEFT_STEP(a, 4) LEFT_STEP(a, 5) LEFT_STEP(a, 6)                                      \
      lo = vec3(kInfinity), hi = -lo;                                                      \
      n = 0.0;                                                                             \
      RIGHT_STEP(a, 7, 6) RIGHT_STEP(a, 6, 5) RIGHT_STEP(a, 5, 4) RIGHT_STEP(a, 4, 3)      \
      RIGHT_STEP(a, 3, 2) RIGHT_STEP(a, 2, 1) RIGHT_STEP(a, 1, 0)                          \
    }
    SWEEP_AXIS(0)
    SWEEP_AXIS(1)
    SWEEP_AXIS(2)
#undef SWEEP_AXIS
#undef RIGHT_STEP
#undef LEFT_STEP
#undef BIN_COUNT
#undef BIN_HI
#undef BIN_LO
    vec3 bestLo[2] = vec3[2](bestLo0, bestLo1), bestHi[2] = vec3[2](bestHi0, bestHi1);

    if (count <= params.maxLeaf && float(count) <= bestCost) {
      nodes[node].leftOrFirst = task.first + first;
      nodes[node].count = count;
      packedNodes[node].w = packLeftOrFirstCount(task.first + first, count);
      atomicAdd(counters.leafCount, 1u);
      continue;
    }
    // No split of finite cost (every centroid in one place), or one that would leave too many
    // primitives for the levels left: the range is halved as it is.
    const bool halved = bestLeft == 0u || !keepsDepthBound(level, max(bestLeft, count - bestLeft));
    if (halved) bestLeft = count / 2u;
    // Stable partition (the left side first, each side in the order it had), and each side's
    // centroid bounds.
    vec3 sideCentreLo[2] = vec3[2](vec3(kInfinity), vec3(kInfinity)), sideCentreHi[2] = vec3[2](-vec3(kInfinity), -vec3(kInfinity));
    uint leftAt = 0u, rightAt = bestLeft;
    for (uint k = 0; k < count; ++k) {
      const uint primitive = order[first + k];
      const vec3 c = centroidOf(boxAt(primitive));
      const bool toRight = halved ? k >= bestLeft : binOf(c[bestAxis], centreLo[bestAxis], scale[bestAxis]) > bestBin;
      if (toRight) sideCentreLo[1] = min(sideCentreLo[1], c), sideCentreHi[1] = max(sideCentreHi[1], c);
      else sideCentreLo[0] = min(sideCentreLo[0], c), sideCentreHi[0] = max(sideCentreHi[0], c);
      if (!halved) reordered[toRight ? rightAt++ : leftAt++] = primitive;
    }
    if (!halved)
      for (uint k = 0; k < count; ++k) order[first + k] = reordered[k];
    const uint left = atomicAdd(counters.nodeCount, 2u);
    atomicMax(counters.levels, level + 2u);
    nodes[node].leftOrFirst = left;
    nodes[node].count = 0u;
    packedNodes[node].w = packLeftOrFirstCount(left, 0u);
    for (uint side = 0; side < 2; ++side) {
      const uint childFirst = side == 0u ? first : first + bestLeft;
      const uint childCount = side == 0u ? bestLeft : count - bestLeft;
      vec3 lo = side == 0u ? bestLo[0] : bestLo[1], hi = side == 0u ? bestHi[0] : bestHi[1];
      if (halved) {
        lo = vec3(kInfinity), hi = -lo;
        for (uint k = 0; k < childCount; ++k) {
          const BvhBox box = boxAt(order[childFirst + k]);
          lo = min(lo, box.min.xyz);
          hi = max(hi, box.max.xyz);
        }
      }
      writeChild(left + side, task.first + childFirst, childCount, task.tree, lo, hi, PACK_LATER);
      if (childCount <= 1u) continue;
      stackCentreLo[depth] = vec4(side == 0u ? sideCentreLo[0] : sideCentreLo[1], 0.0);
      stackCentreHi[depth] = vec4(side == 0u ? sideCentreHi[0] : sideCentreHi[1], 0.0);
      stack[depth++] = uvec4(left + side, childFirst, childCount, level + 1u);
    }
  }
  for (uint k = 0; k < task.count; ++k) primitives[task.first + k] = order[k];
}
