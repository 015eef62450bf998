#version 450
// The hybrid's background layer, blurred at the ray mask's listed pixels only (an indirect
// dispatch over the list): the raster G-buffer with the revealed surfaces read in its place
// wherever the mask says HMB_MASK_REVEALED, gathered as the post-process gather does
// (mblur/gather_samples.glsl, no mask boosts). Two uses, a specialization constant:
//  - coverage (the default composite): the hybrid's image at the revealed mask pixels X (the
//    list's front). Under the linear-motion convention X is covered by its object at shutter
//    fraction s exactly when X + (1 - s) v_X lies on that object now, so the share of samples
//    X + u v_X, u in (0, 1], that are on it (or not behind X) estimates the coverage alpha, and
//    the object's blurred colour F is the plain mean of those samples (and X):
//    C = alpha F + (1 - alpha) B, B the blurred background at X. v_X is the pixel's own
//    velocity, clamped only to the image (maxSpeed), not to the tile: a fast object's inner blur
//    is as wide as its motion even where the gather's tiles clamp its outer blur. Along curved
//    paths the samples follow the pixel's own curve, X + u v + u^2 q. mask_coverage.comp took
//    those samples before the reveal (they decide which pixels the reveal needs) and kept alpha
//    and F. Blended here, where B is in hand, rather than stored for a pass of its own; the mask
//    pixels not revealed (alpha exactly 1: C = F) are composite.comp's.
//  - background alone, at the list's front, for the weights form's composite (composite.comp).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reveal_layout.h"
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

bool overlaid(uint i) { return rayMaskValue(mask[i / 16u], i) == HMB_MASK_REVEALED; }
uvec4 blurSampleAt(uint i) { return overlaid(i) ? READ_LAYER_SAMPLE(revealed, i) : READ_LAYER_SAMPLE(raster, i); }
vec4 contributionOf(uint sampleIndex, vec4 sampleColor) { return sampleColor; }

// The raster's paths; a revealed surface has none (its samples go straight).
#include "../shared/texel_records.glsl"
layout(binding = HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS) uniform utextureBuffer shutterPathTexels;
// mask_coverage's (F, alpha) per mask pixel, read with the coverage composite.
layout(binding = HMB_BACKGROUND_GATHER_BINDING_COVERAGE) uniform utextureBuffer coverageTexels;
uvec2 shutterPathAt(uint i) { return overlaid(i) ? uvec2(HMB_NO_SHUTTER_PATH) : halfRecordAt(shutterPathTexels, i); }

// Built for the frame's path and range (reveal_layout.h).
layout(constant_id = HMB_SPEC_BACKGROUND_GATHER_CURVED_PATH) const bool kCurvedPath = false;
#define HMB_GATHER_CURVED_PATH_CODE kCurvedPath
layout(constant_id = HMB_SPEC_BACKGROUND_GATHER_ADAPTED_RANGE) const bool kAdaptedRange = true;
#define HMB_GATHER_ADAPTED_RANGE kAdaptedRange
layout(constant_id = HMB_SPEC_BACKGROUND_GATHER_COVERAGE) const bool kCoverage = false;
#include "../mblur/gather_samples.glsl"

// The list's front: the background gathered, then (coverage) blended under the foreground.
void main() {
  const uint entry = linearInvocationIndex(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y);
  if (entry >= counters.maskCount) return;
  const uint index = pixelList[entry];
  const uvec2 pixel = uvec2(index % params.width, index / params.width);
  if (pixel.y >= params.height) return;
  GatherCentre centre;
  const bool blurs = readGatherCentre(pixel, index, centre);
  if (!kCoverage) {
    outColor[index] = blurs ? gatherSamples(pixel, centre, 1.0, 1.0) : centre.color;
    return;
  }
  // Under kMinBlurPixels of blur in the whole neighbourhood (the tile decides, whichever layer is
  // read): the raster's own colour, as the post-process gather leaves it.
  if (!blurs) {
    outColor[index] = sanitizeColor(vec4(sampleColor(READ_LAYER_SAMPLE(raster, index)), 1.0));
    return;
  }
  const vec4 foreground = floatRecordAt(coverageTexels, index);
  const float alpha = foreground.w;
  outColor[index] =
      alpha * vec4(foreground.rgb, 1.0) + (1.0 - alpha) * sanitizeColor(gatherSamples(pixel, centre, 1.0, 1.0));
}
