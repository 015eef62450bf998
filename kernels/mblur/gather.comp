#version 450
// The post-process gather: McGuire et al. 2012's reconstruction with the paper's weights and
// its centred or adapted range (mblur/gather_samples.glsl), every pixel of the moving blocks
// (list_gather_blocks.comp; copy_still_blocks.comp writes the others); for the hybrid on a GPU
// (HMB_SPEC_GATHER_OUTSIDE_MASK) every such pixel outside its ray mask, whose pixels its
// composite writes: a lane group wholly inside the mask then costs a load. (A CPU device runs
// every lane of a vector: there the hybrid takes the plain build, HybridStage::record.)
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "filter_bindings.glsl"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;
layout(push_constant) uniform Params { GatherParams params; };
layout(constant_id = HMB_SPEC_GATHER_OUTSIDE_MASK) const bool kOutsideMask = false;
// The curved path's code (HMB_GATHER_FLAG_CURVED_PATH) compiled in: only for frames that take it.
layout(constant_id = HMB_SPEC_GATHER_CURVED_PATH) const bool kCurvedPath = false;
#define HMB_GATHER_CURVED_PATH_CODE kCurvedPath
// The range (HMB_GATHER_FLAG_ADAPTED_RANGE), compiled in: the other's code would run too.
layout(constant_id = HMB_SPEC_GATHER_ADAPTED_RANGE) const bool kAdaptedRange = true;
#define HMB_GATHER_ADAPTED_RANGE kAdaptedRange
layout(std430, binding = HMB_GATHER_BINDING_MASK) readonly buffer Mask { uint mask[]; };
layout(std430, binding = HMB_GATHER_BINDING_BLOCKS) readonly buffer Blocks { uint blocks[]; };
layout(std430, binding = HMB_GATHER_BINDING_BLOCK_COUNTERS) readonly buffer Counters { GatherBlockCounters counters; };

uvec4 blurSampleAt(uint i) { return layerSampleAt(i); }
vec4 contributionOf(uint sampleIndex, vec4 sampleColor) { return sampleColor; }

#include "gather_samples.glsl"

void main() {
  const uint slot = foldedGroupIndex();  // the list's dispatch: HMB_GATHER_BLOCKS_PER_ROW a row
  if (slot >= counters.lists[HMB_GATHER_BLOCKS_MOVING].count) return;
  const uvec2 pixel = gatherBlockPlace(blocks[slot]) * HMB_GATHER_BLOCK + gl_LocalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  if (kOutsideMask && rayMaskValue(mask[index / 16u], index) != 0u) return;
  GatherCentre centre;
  outColor[index] = readGatherCentre(pixel, index, centre) ? gatherSamples(pixel, centre, 1.0, 1.0) : centre.color;
}
