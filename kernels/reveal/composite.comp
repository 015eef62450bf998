#version 450
// The hybrid composite (paper, section 3: both layers blurred, then composited; the paper leaves
// the form open) at the pixels of the ray mask, one invocation per entry of the mask's pixel list
// (an indirect dispatch). Outside the mask the hybrid's image is the post-process gather of the
// raster layer, which has written every pixel before this pass: run apart, the gather keeps its
// own cost and a GPU's warps do not diverge between the two forms. At a mask pixel X the raster
// holds the moving object, and the samples the gather takes behind X (other objects deeper than
// X) are the wrong background: what lies beyond the silhouette, not behind X. The background
// layer blurred at mask pixels (gather_background.comp) gives B, the right background at X. Two
// forms, a specialization constant:
//  - weights: at every mask pixel (the list's front), the gather with the paper's mask boosts
//    (w_b x maskBackgroundBoost, w_f / maskForegroundDivide: x3 and /3), each sample's colour
//    becoming mix(c_s, B, b), b its share behind X.
//  - coverage (default): C = alpha F + (1 - alpha) B (gather_background.comp gives the form and
//    blends it at the revealed pixels); here the list's back, the mask pixels whose samples all
//    stay on their object: alpha is exactly 1 and C = F, mask_coverage's foreground.
// The README gives the measured errors.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reveal_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/indexing.glsl"
#include "../shared/layer_bindings.glsl"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;

// The neighbour-max, the blurred background and the mask's coverage, read at per-lane
// addresses: uniform texel buffers (shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_COMPOSITE_BINDING_NEIGHBOR_MAX) uniform utextureBuffer neighborMaxTexels;
layout(binding = HMB_COMPOSITE_BINDING_BACKGROUND) uniform utextureBuffer backgroundTexels;
vec4 neighborMaxAt(uint tile) { return floatRecordAt(neighborMaxTexels, tile); }
vec4 backgroundAt(uint index) { return floatRecordAt(backgroundTexels, index); }
layout(binding = HMB_COMPOSITE_BINDING_COVERAGE) uniform utextureBuffer coverageTexels;
layout(std430, binding = HMB_COMPOSITE_BINDING_LIST) readonly buffer List { uint pixelList[]; };
layout(std430, binding = HMB_COMPOSITE_BINDING_COUNTERS) readonly buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_COMPOSITE_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };
HMB_LAYER_TEXELS(raster, HMB_COMPOSITE_BINDING_RASTER)
layout(push_constant) uniform Params { GatherParams params; };

// Built for the frame's path and range (reveal_layout.h).
layout(constant_id = HMB_SPEC_COMPOSITE_CURVED_PATH) const bool kCurvedPath = false;
#define HMB_GATHER_CURVED_PATH_CODE kCurvedPath
layout(constant_id = HMB_SPEC_COMPOSITE_ADAPTED_RANGE) const bool kAdaptedRange = true;
#define HMB_GATHER_ADAPTED_RANGE kAdaptedRange
layout(constant_id = HMB_SPEC_COMPOSITE_COVERAGE) const bool kCoverage = true;

#include "../mblur/mblur_common.glsl"

// At the current pixel: the blurred background B, the pixel's object and depth.
vec4 blurredBackground = vec4(0.0);
uint centreObject = 0u;
float compositeCentreDepth = 0.0;

uvec4 blurSampleAt(uint i) { return READ_LAYER_SAMPLE(raster, i); }

// Share of sample `sampleIndex` that is background to the pixel (object `object` at `depth`).
float behindShare(uint sampleIndex, uint object, float depth) {
  const uvec4 surface = READ_LAYER_SURFACE(raster, sampleIndex);  // id and depth in one load
  return behindShareOf(surfaceObjectId(surface), sanitizeDepth(surfaceDepth(surface)), object, depth, params.softZExtent);
}

vec4 contributionOf(uint sampleIndex, vec4 sampleColor) {
  return mix(sampleColor, blurredBackground, behindShare(sampleIndex, centreObject, compositeCentreDepth));
}

layout(binding = HMB_COMPOSITE_BINDING_SHUTTER_PATHS) uniform utextureBuffer shutterPathTexels;
uvec2 shutterPathAt(uint i) { return halfRecordAt(shutterPathTexels, i); }

#include "../mblur/gather_samples.glsl"

void main() {
  const uint entry = linearInvocationIndex(HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y);
  if (entry >= (kCoverage ? counters.unrevealedCount : counters.maskCount)) return;
  // The coverage form reads the list's back, from its end inwards.
  const uint index = pixelList[kCoverage ? params.width * params.height - 1u - entry : entry];
  const uvec2 pixel = uvec2(index % params.width, index / params.width);
  if (pixel.y >= params.height) return;
  GatherCentre centre;
  if (!readGatherCentre(pixel, index, centre)) {
    outColor[index] = centre.color;
    return;
  }
  if (kCoverage) {
    outColor[index] = vec4(floatRecordAt(coverageTexels, index).rgb, 1.0);
    return;
  }
  blurredBackground = sanitizeColor(backgroundAt(index));
  centreObject = surfaceObjectId(READ_LAYER_SURFACE(raster, index));
  compositeCentreDepth = centre.depth;
  outColor[index] = gatherSamples(pixel, centre, 1.0 / params.maskForegroundDivide, params.maskBackgroundBoost);
}
