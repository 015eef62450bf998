#version 450
// Ray mask, with the coverage composite: the mask's list, block by block (ray_mask_layout.h). One
// lane per 8 x 8 block of the image: the bits mask_coverage set for the block's pixels, then
// those needing the reveal at the list's front and the others at its back, each side with one
// atomic, in row order.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../shared/indexing.glsl"
#include "../shared/texel_records.glsl"

layout(local_size_x = HMB_LIST_MASK_BLOCKS_GROUP) in;

layout(binding = HMB_LIST_MASK_BLOCKS_BINDING_BLOCK_BITS) uniform utextureBuffer blockBitTexels;
layout(std430, binding = HMB_LIST_MASK_BLOCKS_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_LIST_MASK_BLOCKS_BINDING_LIST) writeonly buffer List { uint list[]; };
layout(push_constant) uniform Params { RayMaskParams params; };

// Lists the pixels of `bits` (two words: a bit per pixel of the block at `origin`) from `at` on,
// `step` apart (1 from the front, -1 from the back).
void listBits(uvec2 bits, uvec2 origin, uint at, uint step) {
  for (uint word = 0u; word < 2u; ++word) {
    uint left = bits[word];
    while (left != 0u) {
      const uint bit = word * 32u + uint(findLSB(left));
      left &= left - 1u;
      list[at] = (origin.y + bit / HMB_MASK_BLOCK) * params.blur.width + origin.x + bit % HMB_MASK_BLOCK;
      at += step;
    }
  }
}

void main() {
  const uint blocksAcross = HMB_MASK_BLOCKS_ACROSS(params.blur.width);
  const uint block = linearInvocationIndex(HMB_LIST_MASK_BLOCKS_GROUP);
  if (block >= blocksAcross * HMB_MASK_BLOCKS_ACROSS(params.blur.height)) return;
  const uvec4 bits = recordAt(blockBitTexels, block);
  const uint front = bitCount(bits.x) + bitCount(bits.y), back = bitCount(bits.z) + bitCount(bits.w);
  if (front + back == 0u) return;
  const uvec2 origin = uvec2(block % blocksAcross, block / blocksAcross) * HMB_MASK_BLOCK;
  if (front != 0u) listBits(bits.xy, origin, atomicAdd(counters.maskCount, front), 1u);
  if (back != 0u)
    listBits(bits.zw, origin, params.blur.width * params.blur.height - 1u - atomicAdd(counters.unrevealedCount, back),
             ~0u);
}
