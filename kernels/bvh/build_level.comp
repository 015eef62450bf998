#version 450
// One level of the top-down binned SAH build, one workgroup per task. The workgroup bins the
// task's primitives by centroid on each axis (up to HMB_BVH_BINS bins across the centroid
// bounds), costs every bin boundary by the surface area heuristic, and either makes the node a
// leaf (at most params.maxLeaf primitives and no split cheaper) or partitions the range into
// two child nodes; halved in the middle instead where the split would leave its larger side
// too many primitives for the levels left (HMB_BVH_MAX_DEPTH). A large task bins a sample of
// its primitives (HMB_BVH_BIN_SAMPLE), where no split could break that bound. A child of one
// primitive becomes a leaf at once; others are the next level's tasks. Primitive ranges alternate between the two halves of the primitive buffer by
// level parity; every leaf leaves its primitives in the first half, the final order.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#extension GL_EXT_control_flow_attributes : require
#include "bvh_build_common.glsl"
#include "../shared/ordered_float.glsl"

#define BINS HMB_BVH_BINS
#define LEAF_SPLIT (-1)
#define MEDIAN_SPLIT (-2)
// lavapipe ends an invocation's loops after 65535 iterations in all (its guard against endless
// loops), silently. The two loops over a task's primitives take UNROLL primitives per lane
// and iteration, so that a task of HMB_BVH_MAX_TREE_PRIMITIVES stays under that count.
#define UNROLL 8

// The workgroup's size and how it bins come from the device (BvhBuildShape): on a CPU
// device 8 lanes binning large tasks into a copy of the bins per lane; on a GPU a warp or
// wave binning with shared atomics, and no per-lane copies.
layout(local_size_x = HMB_BVH_LEVEL_GROUP, local_size_x_id = HMB_SPEC_BVH_LEVEL_GROUP) in;
layout(constant_id = HMB_SPEC_BVH_LANE_BINS) const bool kLaneBins = true;
// Tasks of at most this many primitives are left to build_small_tasks (bvh_build_layout.h).
layout(constant_id = HMB_SPEC_BVH_LEVEL_SMALL_TASK) const uint kSmallTask = HMB_BVH_SMALL_TASK;
const uint GROUP = gl_WorkGroupSize.x;
const uint LANE_SLOTS = kLaneBins ? GROUP * 3u * BINS : 1u;

#define kInfinity uintBitsToFloat(0x7f800000u)

// Per lane, per (axis, bin): the merged boxes' lower corner with the primitive count in w (a
// float: exact to 2^24, past any lane's share of a tree), and their upper corner. One vec4 per
// side, so binning a primitive is two loads and two stores per axis: on lavapipe each
// shared-memory access at per-lane addresses is a loop over the lanes, whatever its width.
shared vec4 laneBinLower[LANE_SLOTS];
shared vec4 laneBinUpper[LANE_SLOTS];
// The bins of the whole task: the lower corner (ordered uints, see ordered_float.glsl) with
// the count in w, and the upper corner; one access per side (shared atomics work on their
// components). Then each axis's left-to-right sweep: per (axis, bin b), the area of bins
// 0..b merged and the primitives in them.
shared uvec4 binLowerCount[3 * BINS];
shared uvec4 binUpper[3 * BINS];
shared vec2 leftAreaCount[3 * BINS];  // x: area, y: count (exact in a float up to 2^24)
shared float axisCost[3];           // the cheapest split of each axis (+inf: none)
shared uint axisSplit[3];           // its last bin on the left
shared int chosenSplit;             // the axis split along, or LEAF_SPLIT / MEDIAN_SPLIT
shared uint firstChild;
shared uint cursor[2];
// Per lane, per side: box min, box max, centroid min, centroid max of what it sent there
// (xyz of 4 vec4 per side), then the same merged over the lanes.
shared vec4 laneChildBounds[GROUP * 8];
shared vec4 childBounds[8];

// Bin of a centroid coordinate among `bins`; scale is 0 on an axis whose centroids coincide
// (not binned).
uint binOf(float c, float lo, float scale, uint bins) {
  return uint(clamp((c - lo) * scale, 0.0, float(bins - 1u)));
}

vec3 unordered(uvec3 ordered) {
  return vec3(orderedFloat(ordered.x), orderedFloat(ordered.y), orderedFloat(ordered.z));
}

// A small task bins straight into the task's bins with shared atomics: cheaper than setting
// up and merging a copy per lane when each lane bins only a few primitives.
void binWithAtomics(BvhBuildTask task, uint inBase, vec3 scale, uint bins, uint stride, uint lane) {
  for (uint i = lane; i < 3 * BINS; i += GROUP) {
    binLowerCount[i] = uvec4(uvec3(kOrderedPositiveInfinity), 0u);
    binUpper[i] = uvec4(uvec3(kOrderedNegativeInfinity), 0u);
  }
  barrier();
  for (uint k = lane * stride; k < task.count; k += GROUP * stride) {
    const BvhBox box = boxAt(primitives[inBase + task.first + k]);
    const vec3 c = centroidOf(box);
    for (uint a = 0; a < 3; ++a) {
      if (scale[a] == 0.0) continue;
      const uint slot = a * BINS + binOf(c[a], task.centroidMin[a], scale[a], bins);
      atomicAdd(binLowerCount[slot].w, 1u);
      atomicMin(binLowerCount[slot].x, orderedUint(box.min.x));
      atomicMin(binLowerCount[slot].y, orderedUint(box.min.y));
      atomicMin(binLowerCount[slot].z, orderedUint(box.min.z));
      atomicMax(binUpper[slot].x, orderedUint(box.max.x));
      atomicMax(binUpper[slot].y, orderedUint(box.max.y));
      atomicMax(binUpper[slot].z, orderedUint(box.max.z));
    }
  }
}

// A large task bins into a copy per lane, without atomics, then merges the copies.
void binPerLane(BvhBuildTask task, uint inBase, vec3 scale, uint bins, uint stride, uint lane) {
  const uint mine = lane * 3 * BINS;
  for (uint a = 0; a < 3; ++a)
    for (uint b = 0; b < bins; ++b) {
      laneBinLower[mine + a * BINS + b] = vec4(vec3(kInfinity), 0.0);
      laneBinUpper[mine + a * BINS + b] = vec4(-vec3(kInfinity), 0.0);
    }
  const uint samples = (task.count + stride - 1u) / stride;
  for (uint base = lane; base < samples; base += GROUP * UNROLL) [[unroll]] for (uint u = 0; u < UNROLL; ++u) {
    const uint j = base + u * GROUP;
    if (j >= samples) break;
    const BvhBox box = boxAt(primitives[inBase + task.first + j * stride]);
    const vec3 c = centroidOf(box);
    for (uint a = 0; a < 3; ++a) {
      if (scale[a] == 0.0) continue;
      const uint slot = mine + a * BINS + binOf(c[a], task.centroidMin[a], scale[a], bins);
      const vec4 lower = laneBinLower[slot];
      laneBinLower[slot] = vec4(min(lower.xyz, box.min.xyz), lower.w + 1.0);
      laneBinUpper[slot].xyz = max(laneBinUpper[slot].xyz, box.max.xyz);
    }
  }
  barrier();
  for (uint i = lane; i < 3 * bins; i += GROUP) {
    const uint slot = (i / bins) * BINS + i % bins;
    float n = 0.0;
    vec3 lo = vec3(kInfinity), hi = -lo;
    for (uint l = 0; l < GROUP; ++l) {
      const vec4 lower = laneBinLower[l * 3 * BINS + slot];
      n += lower.w;
      lo = min(lo, lower.xyz);
      hi = max(hi, laneBinUpper[l * 3 * BINS + slot].xyz);
    }
    binLowerCount[slot] = uvec4(orderedUint(lo.x), orderedUint(lo.y), orderedUint(lo.z), uint(n));
    binUpper[slot] = uvec4(orderedUint(hi.x), orderedUint(hi.y), orderedUint(hi.z), 0u);
  }
}

void main() {
  const uint parity = params.level & 1u;
  const uint taskIndex = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (taskIndex >= counters.taskCount[parity]) return;  // uniform across the workgroup
  const uint lane = gl_LocalInvocationID.x;
  const BvhBuildTask task = tasks[parity * params.taskCapacity + taskIndex];
  const uint inBase = parity * params.primitiveCount;
  const uint outBase = (1u - parity) * params.primitiveCount;

  // Bins span the centroid bounds; a small range gets one bin per primitive. The scale stays
  // finite so that no 0 * inf makes a NaN bin.
  const uint bins = clamp(task.count, 2u, uint(BINS));
  const vec3 extent = task.centroidMax.xyz - task.centroidMin.xyz;
  vec3 scale;
  for (uint a = 0; a < 3; ++a)
    scale[a] = extent[a] > 0.0 && !isinf(extent[a]) ? min(float(bins) / extent[a], 3.0e38) : 0.0;

  // A sample where every split keeps the depth bound (the sample's counts cannot tell).
  const uint stride = keepsDepthBound(params.level, task.count) ? max(1u, task.count / HMB_BVH_BIN_SAMPLE) : 1u;
  if (kLaneBins && task.count >= HMB_BVH_LANE_BINS_MIN) binPerLane(task, inBase, scale, bins, stride, lane);
  else binWithAtomics(task, inBase, scale, bins, stride, lane);
  barrier();

  // Each axis's splits "bins 0..s left, s+1.. right" costed in two sweeps by one lane per
  // axis: left to right stores the left sides, right to left costs each split. A sample's
  // counts stand for stride primitives each.
  const BvhNode node = nodes[task.node];
  const float nodeArea = surfaceArea(vec3(node.minX, node.minY, node.minZ), vec3(node.maxX, node.maxY, node.maxZ));
  if (lane < 3) {
    const uint a = lane;
    float best = kInfinity;
    uint bestSplit = 0u;
    if (scale[a] != 0.0) {
      vec3 lo = vec3(kInfinity), hi = -lo;
      uint n = 0u;
      for (uint b = 0; b + 1 < bins; ++b) {
        const uint slot = a * BINS + b;
        const uvec4 lower = binLowerCount[slot];
        n += lower.w;
        lo = min(lo, unordered(lower.xyz));
        hi = max(hi, unordered(binUpper[slot].xyz));
        leftAreaCount[slot] = vec2(surfaceArea(lo, hi), float(n));
      }
      lo = vec3(kInfinity), hi = -lo;
      n = 0u;
      for (uint b = bins - 1u; b > 0u; --b) {
        const uint slot = a * BINS + b;
        const uvec4 lower = binLowerCount[slot];
        n += lower.w;
        lo = min(lo, unordered(lower.xyz));
        hi = max(hi, unordered(binUpper[slot].xyz));
        const vec2 leftSide = leftAreaCount[slot - 1u];
        const uint left = uint(leftSide.y);
        if (left == 0u || n == 0u) continue;
        // A node with no area (all primitives on a line or a point) weighs children equally.
        const float leftShare = nodeArea > 0.0 ? leftSide.x / nodeArea : 1.0;
        const float rightShare = nodeArea > 0.0 ? surfaceArea(lo, hi) / nodeArea : 1.0;
        const float cost = 1.0 + (leftShare * float(left) + rightShare * float(n)) * float(stride);
        if (cost <= best) best = cost, bestSplit = b - 1u;  // ties: the lowest split
      }
    }
    axisCost[a] = best;
    axisSplit[a] = bestSplit;
  }
  barrier();

  if (lane == 0) {
    int best = LEAF_SPLIT;
    float bestCost = kInfinity;
    for (int a = 0; a < 3; ++a)
      if (axisCost[a] < bestCost) best = a, bestCost = axisCost[a];
    const bool mayBeLeaf = task.count <= params.maxLeaf;
    if (mayBeLeaf && (best == LEAF_SPLIT || float(task.count) <= bestCost)) best = LEAF_SPLIT;
    else if (best == LEAF_SPLIT) best = MEDIAN_SPLIT;  // centroids coincide: halve the range
    else {
      const uint left = uint(leftAreaCount[uint(best) * BINS + axisSplit[best]].y);
      if (!keepsDepthBound(params.level, max(left, task.count - left))) best = MEDIAN_SPLIT;
    }
    chosenSplit = best;
    if (best != LEAF_SPLIT) {
      firstChild = atomicAdd(counters.nodeCount, 2u);
      cursor[0] = 0u;
      cursor[1] = 0u;
    }
  }
  barrier();

  const int split = chosenSplit;
  if (split == LEAF_SPLIT) {
    if (parity == 1u)
      for (uint k = lane; k < task.count; k += GROUP) primitives[task.first + k] = primitives[inBase + task.first + k];
    if (lane == 0) {
      nodes[task.node].leftOrFirst = task.first;
      nodes[task.node].count = task.count;
      packedNodes[task.node].w = packLeftOrFirstCount(task.first, task.count);
      atomicAdd(counters.leafCount, 1u);
    }
    return;
  }

  const uint axis = split == MEDIAN_SPLIT ? 0u : uint(split);
  const uint lastLeftBin = split == MEDIAN_SPLIT ? 0u : axisSplit[axis];
  const uint halfCount = task.count / 2u;
  // What this lane sends to each side, merged in registers (no per-primitive shared writes).
  vec3 boxLo[2] = vec3[2](vec3(kInfinity), vec3(kInfinity)), boxHi[2] = vec3[2](-vec3(kInfinity), -vec3(kInfinity));
  vec3 centreLo[2] = boxLo, centreHi[2] = boxHi;
  // The left side fills the range from its start, the right side from its end, so that the
  // sides' sizes (unknown where binning took a sample) are counted as they are filled. A side
  // of one primitive is a leaf at once, its primitive's final place in the first half: at even
  // levels that is this task's input, which other lanes may not have read yet, so the write
  // waits for the barrier below. The lane that placed a side's first primitive keeps it.
  bool placedLeftFirst = false, placedRightFirst = false;
  uint leftFirst = 0u, rightFirst = 0u;
  const uint last = task.first + task.count - 1u;
  for (uint base = lane; base < task.count; base += GROUP * UNROLL) [[unroll]] for (uint u = 0; u < UNROLL; ++u) {
    const uint k = base + u * GROUP;
    if (k >= task.count) break;
    const uint primitive = primitives[inBase + task.first + k];
    const BvhBox box = boxAt(primitive);
    const vec3 c = centroidOf(box);
    const bool right = split == MEDIAN_SPLIT
                           ? k >= halfCount
                           : binOf(c[axis], task.centroidMin[axis], scale[axis], bins) > lastLeftBin;
    const uint placed = atomicAdd(cursor[right ? 1u : 0u], 1u);
    primitives[outBase + (right ? last - placed : task.first + placed)] = primitive;
    if (placed == 0u && right) placedRightFirst = true, rightFirst = primitive;
    if (placed == 0u && !right) placedLeftFirst = true, leftFirst = primitive;
    if (right) {
      boxLo[1] = min(boxLo[1], box.min.xyz), boxHi[1] = max(boxHi[1], box.max.xyz);
      centreLo[1] = min(centreLo[1], c), centreHi[1] = max(centreHi[1], c);
    } else {
      boxLo[0] = min(boxLo[0], box.min.xyz), boxHi[0] = max(boxHi[0], box.max.xyz);
      centreLo[0] = min(centreLo[0], c), centreHi[0] = max(centreHi[0], c);
    }
  }
  for (uint side = 0; side < 2; ++side) {
    laneChildBounds[lane * 8 + side * 4] = vec4(boxLo[side], 0.0);
    laneChildBounds[lane * 8 + side * 4 + 1] = vec4(boxHi[side], 0.0);
    laneChildBounds[lane * 8 + side * 4 + 2] = vec4(centreLo[side], 0.0);
    laneChildBounds[lane * 8 + side * 4 + 3] = vec4(centreHi[side], 0.0);
  }
  barrier();
  const uint leftCount = cursor[0], rightCount = cursor[1];
  if (placedLeftFirst && leftCount == 1u) primitives[task.first] = leftFirst;
  if (placedRightFirst && rightCount == 1u) primitives[last] = rightFirst;
  for (uint i = lane; i < 8; i += GROUP) {
    const bool lower = (i & 1u) == 0u;  // box min, box max, centroid min, centroid max per side
    vec3 v = vec3(lower ? kInfinity : -kInfinity);
    for (uint l = 0; l < GROUP; ++l) v = lower ? min(v, laneChildBounds[l * 8 + i].xyz) : max(v, laneChildBounds[l * 8 + i].xyz);
    childBounds[i] = vec4(v, 0.0);
  }
  barrier();

  const uint left = firstChild;
  // Job 0: the node; 1 and 2: the two children.
  for (uint job = lane; job < 3u; job += GROUP) {
    if (job == 0u) {
      nodes[task.node].leftOrFirst = left;
      nodes[task.node].count = 0u;
      packedNodes[task.node].w = packLeftOrFirstCount(left, 0u);
      continue;
    }
    const uint side = job - 1u;
    const uint b = side * 4;
    const uint first = task.first + (side == 0u ? 0u : leftCount);
    const uint count = side == 0u ? leftCount : rightCount;
    writeChild(left + side, first, count, task.tree, childBounds[b].xyz, childBounds[b + 1].xyz, false);
    if (count == 1u) continue;
    BvhBuildTask next;
    next.node = left + side;
    next.first = first;
    next.count = count;
    next.tree = task.tree;
    next.centroidMin = vec4(childBounds[b + 2].xyz, 0.0);
    next.centroidMax = vec4(childBounds[b + 3].xyz, 0.0);
    if (count <= kSmallTask) {
      // Its range is in the half this level wrote; build_small_tasks finishes it after the levels.
      next.centroidMin.w = float(params.level + 1u);
      next.centroidMax.w = float(1u - parity);
      tasks[2u * params.taskCapacity + atomicAdd(counters.smallTaskCount, 1u)] = next;
      continue;
    }
    const uint slot = atomicAdd(counters.taskCount[1u - parity], 1u);
    tasks[(1u - parity) * params.taskCapacity + slot] = next;
    atomicMax(counters.levels, params.level + 2u);
  }
}
