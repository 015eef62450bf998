#version 450
// Ray mask, with the coverage composite: the pixels the range check marked (HMB_MASK_UNREVEALED)
// listed for mask_coverage. A lane per block the range check walked, in its list's order: the
// block's marked pixels in row order, appended with one atomic. (The range check appended each
// itself: an atomic on one counter per mask pixel from every thread of a CPU device, and a list
// in whatever order the threads met them: hybrid_layout.h.)
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "hybrid_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_RANGE_MASK_LIST_GROUP) in;

layout(std430, binding = HMB_RANGE_MASK_LIST_BINDING_BLOCKS) readonly buffer Blocks { uint blockList[]; };
layout(std430, binding = HMB_RANGE_MASK_LIST_BINDING_MASK) readonly buffer Mask { uint mask[]; };
layout(std430, binding = HMB_RANGE_MASK_LIST_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_RANGE_MASK_LIST_BINDING_LIST) writeonly buffer List { uint list[]; };
layout(push_constant) uniform Params { RayMaskParams params; };

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

// A row of the block: its first pixel and its two mask words (a row of at most 8 pixels spans
// at most two of 16), so that its pixels are read with two loads.
struct BlockRow {
  uint first;
  uint firstWord;
  uvec2 words;
};

BlockRow blockRow(uvec2 origin, uint y, uint across) {
  BlockRow row;
  row.first = (origin.y + y) * params.blur.width + origin.x;
  row.firstWord = row.first / 16u;
  row.words = uvec2(mask[row.firstWord], mask[(row.first + across - 1u) / 16u]);
  return row;
}

bool marked(BlockRow row, uint x) {
  const uint at = row.first + x;
  return rayMaskValue(at / 16u == row.firstWord ? row.words.x : row.words.y, at) != HMB_MASK_NONE;
}

void main() {
  const uint entry = linearInvocationIndex(HMB_RANGE_MASK_LIST_GROUP);
  if (entry >= counters.rangeBlockCount) return;
  const uint listed = blockList[entry];
  const uvec2 origin = rangeBlockOrigin(listed);
  // The block's pixels inside its tile and the image, as the range check walked them.
  const uvec2 side = min(rangeBlockSide(listed, params.blur.tileSize), uvec2(params.blur.width, params.blur.height) - origin);
  uint count = 0u;
  for (uint y = 0u; y < side.y; ++y) {
    const BlockRow row = blockRow(origin, y, side.x);
    for (uint x = 0u; x < side.x; ++x) count += marked(row, x) ? 1u : 0u;
  }
  if (count == 0u) return;
  uint at = atomicAdd(counters.coverageCount, count);
  for (uint y = 0u; y < side.y; ++y) {
    const BlockRow row = blockRow(origin, y, side.x);
    for (uint x = 0u; x < side.x; ++x)
      if (marked(row, x)) list[at++] = row.first + x;
  }
}
