#version 450
// Ray mask, with the coverage composite: the pixels the range check marked (HMB_MASK_UNREVEALED)
// listed for mask_coverage. A lane per block the range check walked, in its list's order: the
// block's marked pixels in row order, appended with one atomic. (The range check appended each
// itself: an atomic on one counter per mask pixel from every thread of a CPU device, and a list
// in whatever order the threads met them: ray_mask_layout.h.)
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
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

// A row of the block (at most 8 pixels, within two of the mask's 16-pixel words): a bit per
// marked pixel, at bit 2 * x for pixel x, read with two loads and a few bit operations, so that
// the lane's loop runs over the row's marked pixels alone.
struct BlockRow {
  uint first;   // the row's first pixel
  uint marked;  // any value but HMB_MASK_NONE
};

BlockRow blockRow(uvec2 origin, uint y, uint across) {
  BlockRow row;
  row.first = (origin.y + y) * params.blur.width + origin.x;
  const uint shift = 2u * (row.first % 16u);
  const uint low = mask[row.first / 16u], high = mask[(row.first + across - 1u) / 16u];
  // The row's 2 x across bits, from its first pixel's on (a shift by 32 is undefined: none).
  const uint bits = (shift == 0u ? low : (low >> shift) | (high << (32u - shift))) & (0xFFFFu >> (16u - 2u * across));
  row.marked = (bits | (bits >> 1u)) & 0x5555u;
  return row;
}

// Lists the row's pixels whose bits are set in `bits`, from `at` on.
void listRow(uint first, uint bits, inout uint at) {
  for (; bits != 0u; bits &= bits - 1u) list[at++] = first + uint(findLSB(bits)) / 2u;
}

void main() {
  const uint entry = linearInvocationIndex(HMB_RANGE_MASK_LIST_GROUP);
  if (entry >= counters.rangeBlockCount) return;
  const uint listed = blockList[entry];
  const uvec2 origin = rangeBlockOrigin(listed);
  // The block's pixels inside its tile and the image, as the range check walked them.
  const uvec2 side = min(rangeBlockSide(listed, params.blur.tileSize), uvec2(params.blur.width, params.blur.height) - origin);
  uint count = 0u;
  for (uint y = 0u; y < side.y; ++y) count += bitCount(blockRow(origin, y, side.x).marked);
  if (count == 0u) return;
  uint at = atomicAdd(counters.coverageCount, count);
  for (uint y = 0u; y < side.y; ++y) {
    const BlockRow row = blockRow(origin, y, side.x);
    listRow(row.first, row.marked, at);
  }
}
