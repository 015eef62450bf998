#version 450
// Ray mask, last pass with the coverage composite (composite.comp): at each pixel the range
// check marked (list_range_mask lists them), the coverage composite's foreground. The pixel's samples X + u v, u in (0, 1]
// (along curved paths its own curve X + u v + u^2 q), as the composite takes them: the share on
// the pixel's object (or not behind it) is alpha, and the mean colour of those samples and X is
// the object's blurred colour F; the composite later blends F over the blurred background,
// C = alpha F + (1 - alpha) B. A pixel with a sample behind it (alpha < 1, or a share too small
// to move alpha) is marked HMB_MASK_REVEALED, for the reveal; the others (alpha exactly 1: the
// background gets no weight, their reveal would change nothing) HMB_MASK_UNREVEALED; each sets
// its bit in its block's words, from which list_mask_blocks lists the mask's pixels, those for
// the reveal at the list's front. Tested here, over a list of the mask's pixels alone,
// rather than in the range check: there a CPU device ran the samples of every lane of a vector
// that held one mask pixel.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/indexing.glsl"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_MASK_LIST_GROUP) in;

// The G-buffer's samples (colour, depth) and surfaces (velocity, object id), and the shutter
// paths: uniform texel buffers (shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_MASK_COVERAGE_BINDING_SAMPLES) uniform utextureBuffer sampleTexels;
layout(binding = HMB_MASK_COVERAGE_BINDING_SURFACES) uniform utextureBuffer surfaceTexels;
layout(binding = HMB_MASK_COVERAGE_BINDING_SHUTTER_PATHS) uniform utextureBuffer shutterPathTexels;
uvec4 sampleAt(uint index) { return recordAt(sampleTexels, index); }
uvec4 surfaceAt(uint index) { return recordAt(surfaceTexels, index); }
uvec2 shutterPathAt(uint index) { return halfRecordAt(shutterPathTexels, index); }
layout(std430, binding = HMB_MASK_COVERAGE_BINDING_PIXELS) readonly buffer Pixels { uint maskPixels[]; };
layout(std430, binding = HMB_MASK_COVERAGE_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_MASK_COVERAGE_BINDING_COVERAGE) writeonly buffer Coverage { vec4 coverage[]; };
layout(std430, binding = HMB_MASK_COVERAGE_BINDING_MASK) buffer Mask { uint mask[]; };  // rayMaskBits, turned by atomicXor
layout(std430, binding = HMB_MASK_COVERAGE_BINDING_BLOCK_BITS) buffer BlockBits { uint blockBits[]; };
layout(push_constant) uniform Params { RayMaskParams params; };
layout(constant_id = HMB_SPEC_MASK_COVERAGE_CURVED_PATH) const bool kCurvedPath = false;

#include "../mblur/mblur_common.glsl"
#include "own_curved_path.glsl"

void main() {
  const uint entry = linearInvocationIndex(HMB_MASK_LIST_GROUP);
  if (entry >= counters.coverageCount) return;
  const uint index = maskPixels[entry];
  const uint width = params.blur.width, height = params.blur.height;
  const uvec2 pixel = uvec2(index % width, index / width);
  const uvec4 own = surfaceAt(index);
  const uvec4 ownSample = sampleAt(index);
  const float centreDepth = sanitizeDepth(sampleDepth(ownSample));
  float speed;
  vec2 v = gatherVelocity(surfaceVelocity(own), params.blur.velocityScale, params.blur.maxSpeed, speed);
  vec2 q = vec2(0.0);
  if (kCurvedPath && (params.blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u)
    ownCurvedPath(pixel, index, own, centreDepth, v, q);  // as range_check walks it
  const float jitter = unitFromHash(mblurHash(pixel.x, pixel.y, params.blur.seed));
  const uint object = surfaceObjectId(own);
  vec4 foregroundSum = sanitizeColor(vec4(sampleColor(ownSample), 1.0));
  float foregroundCount = 0.0;
  bool meetsBackground = false;
  for (uint i = 0u; i < params.blur.samples; ++i) {
    const ivec2 p = coverageSamplePixel(pixel, v, q, i, params.blur.samples, jitter, width, height);
    const uint sampleIndex = uint(p.y) * width + uint(p.x);
    const uvec4 record = sampleAt(sampleIndex);
    const float behind = behindShareOf(surfaceObjectId(surfaceAt(sampleIndex)), sanitizeDepth(sampleDepth(record)),
                                       object, centreDepth, params.blur.softZExtent);
    meetsBackground = meetsBackground || behind > 0.0;
    const float onObject = 1.0 - behind;
    foregroundSum += onObject * sanitizeColor(vec4(sampleColor(record), 1.0));
    foregroundCount += onObject;
  }
  // F is opaque: its fourth channel is 1 (the sum's own, 1 + the count added in another order,
  // could round apart), so the fourth word carries alpha.
  const vec3 foreground = foregroundSum.rgb / (1.0 + foregroundCount);
  coverage[index] = vec4(foreground, foregroundCount / float(params.blur.samples));
  // The range check marked it HMB_MASK_UNREVEALED; the reveal's pixels turn to HMB_MASK_REVEALED.
  if (meetsBackground) atomicXor(mask[index / 16u], rayMaskBits(HMB_MASK_UNREVEALED ^ HMB_MASK_REVEALED, index));
  // The pixel's bit in its block's words (list_mask_blocks lists them).
  const uint block = pixel.y / HMB_MASK_BLOCK * HMB_MASK_BLOCKS_ACROSS(width) + pixel.x / HMB_MASK_BLOCK;
  const uint bit = pixel.y % HMB_MASK_BLOCK * HMB_MASK_BLOCK + pixel.x % HMB_MASK_BLOCK;
  atomicOr(blockBits[4u * block + (meetsBackground ? 0u : 2u) + bit / 32u], 1u << (bit % 32u));
}
