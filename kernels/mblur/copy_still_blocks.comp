#version 450
// The gather's still blocks (list_gather_blocks.comp): every pixel keeps its own colour,
// sanitized as the gather sanitizes it, without the gather's reads of its neighbourhood.
// The hybrid's ray mask has no pixel here: it lies in moving tiles, whose blocks are moving
// (a tile's neighbour-max is at least its own tile-max), and its composite runs after.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "mblur_layout.h"
#include "../shared/indexing.glsl"
#include "mblur_common.glsl"
#include "../shared/layer_layout.h"
#include "../shared/texel_records.glsl"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;

layout(binding = HMB_STILL_BLOCKS_BINDING_SAMPLES) uniform utextureBuffer sampleTexels;
layout(std430, binding = HMB_STILL_BLOCKS_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };
layout(std430, binding = HMB_STILL_BLOCKS_BINDING_BLOCKS) readonly buffer Blocks { uint blocks[]; };
layout(std430, binding = HMB_STILL_BLOCKS_BINDING_COUNTERS) readonly buffer Counters { GatherBlockCounters counters; };
layout(push_constant) uniform Params { StillBlocksParams params; };

void main() {
  const uint slot = foldedGroupIndex();  // the list's dispatch: HMB_GATHER_BLOCKS_PER_ROW a row
  if (slot >= counters.lists[HMB_GATHER_BLOCKS_STILL].count) return;
  const uvec2 pixel = gatherBlockPlace(blocks[params.blockCount - 1u - slot]) * HMB_GATHER_BLOCK + gl_LocalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  outColor[index] = sanitizeColor(vec4(sampleColor(recordAt(sampleTexels, index)), 1.0));
}
