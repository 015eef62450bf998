#version 450
// A list's length -> the indirect dispatch of the passes over it, folded into rows of at most
// 65535 groups: the blocks of the moving tiles (a lane each: list_range_blocks) with the edge
// candidates the same tile-max listed (one dispatch sizes both); the moving tiles' 8 x 8 blocks
// (list_shutter_rays) and the range check's listed blocks (range_check): a group per block, or
// as many as wanted, each a run no longer than its walks' loop budget allows (and a lane per
// block: list_range_mask); the edge
// candidates (HMB_MASK_LIST_GROUP each: edge_mask), the range check's mask pixels for the
// coverage test (HMB_MASK_LIST_GROUP each: mask_coverage) or the ray mask's pixels
// (HMB_MASK_LIST_GROUP each: reveal_background, the background layer's gather and the weights
// composite over the list's front, the coverage composite over its back).
// An empty list dispatches no group.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../shared/dispatch.h"

layout(local_size_x = 1) in;

layout(std430, binding = HMB_SIZE_LIST_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(push_constant) uniform Params { SizeListParams params; };

void setDispatch(uint dispatch, uvec3 groups) {
  counters.dispatches[dispatch] = IndirectDispatch(groups.x, groups.y, groups.z);
}

uvec3 listGroups(uint count) { return foldedGroups((count + HMB_MASK_LIST_GROUP - 1u) / HMB_MASK_LIST_GROUP); }

// How far a walk may reach, rounded up: a loop round per pixel it steps.
uint walkRounds() { return uint(ceil(min(params.walkSpeed, 1.0e6))); }

// The most blocks a run may take where each takes `rounds` loop rounds: within the driver's
// loop budget, if it has one.
uint runWithinBudget(uint rounds, uint most) {
  return params.loopBudget == 0u ? most : clamp(params.loopBudget / rounds, 1u, most);
}

// Groups for `count` blocks: one each, or as many as wanted, but never a run past maxRun blocks.
uvec3 runGroups(uint count, uint maxRun) {
  const uint runs = (count + maxRun - 1u) / maxRun;
  return foldedGroups(params.groupsWanted == 0u ? count : max(min(count, params.groupsWanted), runs));
}

void main() {
  if (params.list == HMB_SIZE_LIST_TILES_AND_CANDIDATES) {
    // At most a block per pixel: the product stays far below 2^32.
    const uint blocks = counters.tileCount * params.tileBlocks;
    const uvec3 g = foldedGroups((blocks + HMB_RANGE_BLOCKS_GROUP - 1u) / HMB_RANGE_BLOCKS_GROUP);
    setDispatch(HMB_RAY_MASK_DISPATCH_TILE_BLOCKS, g);
    const uvec3 c = listGroups(counters.candidateCount);
    setDispatch(HMB_RAY_MASK_DISPATCH_CANDIDATES, c);
    return;
  }
  if (params.list == HMB_SIZE_LIST_RANGE_BLOCKS) {
    const uint count = counters.rangeBlockCount;
    const uint maxRun = runWithinBudget(4u * walkRounds() + 17u, HMB_RANGE_CHECK_MAX_RUN);
    const uvec3 g = runGroups(count, maxRun);
    setDispatch(HMB_RAY_MASK_DISPATCH_RANGE_CHECK, g);
    const uvec3 l = foldedGroups((count + HMB_RANGE_MASK_LIST_GROUP - 1u) / HMB_RANGE_MASK_LIST_GROUP);
    setDispatch(HMB_RAY_MASK_DISPATCH_RANGE_LIST, l);
    return;
  }
  if (params.list == HMB_SIZE_LIST_SHUTTER_BLOCKS) {
    const uint count = counters.tileCount * params.tileBlocks;
    const uvec3 g = runGroups(count, runWithinBudget(walkRounds() + 6u, max(count, 1u)));
    setDispatch(HMB_RAY_MASK_DISPATCH_SHUTTER_BLOCKS, g);
    return;
  }
  if (params.list == HMB_SIZE_LIST_COVERAGE) {
    const uvec3 g = listGroups(counters.coverageCount);
    setDispatch(HMB_RAY_MASK_DISPATCH_COVERAGE, g);
    return;
  }
  const uvec3 g = listGroups(counters.maskCount);
  setDispatch(HMB_RAY_MASK_DISPATCH_MASK, g);
  counters.maskPixels = counters.maskCount + counters.unrevealedCount;
  const uvec3 back = listGroups(counters.unrevealedCount);
  setDispatch(HMB_RAY_MASK_DISPATCH_UNREVEALED, back);
}
