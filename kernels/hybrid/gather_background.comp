#version 450
// The hybrid's background layer, blurred at the ray mask's listed pixels only (an indirect
// dispatch over the list): the raster G-buffer with the revealed surfaces read in its place
// wherever the mask says HMB_MASK_REVEALED, gathered as the post-process gather does
// (mblur/gather_samples.glsl, no mask boosts). The composite reads the result at mask pixels.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "hybrid_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/indexing.glsl"
#include "../shared/layer_bindings.glsl"
#include "../gbuffer/gbuffer_layout.h"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;

layout(std430, binding = HMB_BACKGROUND_GATHER_BINDING_NEIGHBOR_MAX) readonly buffer NeighborMax { vec4 neighborMax[]; };
vec4 neighborMaxAt(uint tile) { return neighborMax[tile]; }
layout(std430, binding = HMB_BACKGROUND_GATHER_BINDING_MASK) readonly buffer Mask { uint mask[]; };
layout(std430, binding = HMB_BACKGROUND_GATHER_BINDING_LIST) readonly buffer List { uint pixelList[]; };
layout(std430, binding = HMB_BACKGROUND_GATHER_BINDING_COUNTERS) readonly buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_BACKGROUND_GATHER_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };
HMB_LAYER_TEXELS(raster, HMB_BACKGROUND_GATHER_BINDING_RASTER)
HMB_LAYER_TEXELS(revealed, HMB_BACKGROUND_GATHER_BINDING_REVEALED)
layout(push_constant) uniform Params { GatherParams params; };

bool overlaid(uint i) { return mask[i] == HMB_MASK_REVEALED; }
uvec4 blurSampleAt(uint i) { return overlaid(i) ? READ_LAYER_SAMPLE(revealed, i) : READ_LAYER_SAMPLE(raster, i); }
vec4 contributionOf(uint sampleIndex, vec4 sampleColor) { return sampleColor; }

// The raster's paths; a revealed surface has none (its samples go straight).
#include "../shared/texel_records.glsl"
layout(binding = HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS) uniform utextureBuffer shutterPathTexels;
uvec2 shutterPathAt(uint i) { return overlaid(i) ? uvec2(HMB_NO_SHUTTER_PATH) : halfRecordAt(shutterPathTexels, i); }

// Built for the frame's path and range (hybrid_layout.h).
layout(constant_id = HMB_SPEC_BACKGROUND_GATHER_CURVED_PATH) const bool kCurvedPath = false;
#define HMB_GATHER_CURVED_PATH_CODE kCurvedPath
layout(constant_id = HMB_SPEC_BACKGROUND_GATHER_ADAPTED_RANGE) const bool kAdaptedRange = true;
#define HMB_GATHER_ADAPTED_RANGE kAdaptedRange
#include "../mblur/gather_samples.glsl"

void main() {
  const uint entry = linearInvocationIndex(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y);
  if (entry >= counters.maskCount) return;
  const uint index = pixelList[entry];
  const uvec2 pixel = uvec2(index % params.width, index / params.width);
  if (pixel.y >= params.height) return;
  GatherCentre centre;
  outColor[index] = readGatherCentre(pixel, index, centre) ? gatherSamples(pixel, centre, 1.0, 1.0) : centre.color;
}
