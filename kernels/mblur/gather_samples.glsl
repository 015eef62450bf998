// The sum over one pixel's samples of McGuire et al. 2012's reconstruction with the paper's
// appendix weights (eqs. 5-10):
//   w = w_f + w_b + w_s, z = (z_t - z_s) / SOFT_Z_EXTENT,
//   w_f = saturate(1 + z) saturate(1 - ds / v_s)   (sample in front, its blur reaches the pixel)
//   w_b = saturate(1 - z) saturate(1 - ds / v_t)   (sample behind, seen through the pixel's blur)
//   w_s = cylinder(v_s, ds) cylinder(v_t, ds) 2    (both blurred over each other)
// sampling along v_N, the neighbour-max velocity of the pixel's tile, S samples jittered per
// pixel by a hash of (pixel, seed), read at the nearest pixel clamped to the image.
//
// Two ranges (the paper's Figure 3):
//  - centred (McGuire's original): half per-exposure velocities, samples at X + t v_N with
//    t = mix(-1, 1, (i + j + 1) / (S + 1)), j in [-0.5, 0.5); for odd S the middle sample,
//    which lands on X itself, is skipped since X is already counted.
//  - adapted (the paper): full per-exposure velocities and the pixel at the end of its range,
//    samples at X + u v_N with u = (i + 1 - r) / S in (0, 1], r in [0, 1) (design convention:
//    X sees the points now at X + u v, u in [0, 1]).
// The pixel itself weighs 1 / max(|v_X|, 0.5) (McGuire: a pixel moving |v| px covers itself
// for 1/|v| of the exposure; 0.5 px bounds the weight of still pixels at 2). w_f is multiplied
// by foregroundBoost when the pixel is deeper than the sample by at least SOFT_Z_EXTENT (the
// paper's section 4: x30 for the adapted range).
//
// Shared by the post-process gather (mblur/gather.comp) and the hybrid's gathers
// (hybrid/gather_background.comp, hybrid/composite.comp). The including kernel declares
// `params` (GatherParams) and defines, before including this file, what a sample reads:
//   uvec4 blurSampleAt(uint i)  (pixel i's packed sample: colour, depth, velocity, one load;
//                                shared/layer_layout.h),
//   vec4 contributionOf(uint sampleIndex, vec4 sampleColor)  (the colour a sample adds),
//   vec4 neighborMaxAt(uint tile)  (the tile's neighbour-max velocity).
#ifndef HMB_KERNELS_MBLUR_GATHER_SAMPLES_GLSL
#define HMB_KERNELS_MBLUR_GATHER_SAMPLES_GLSL

#include "mblur_common.glsl"
#include "../shared/layer_layout.h"

// What a gather reads of its own pixel.
struct GatherCentre {
  vec4 color;     // sanitized
  vec2 dominant;  // its tile's neighbour-max velocity
  float speed;    // its own, clamped to the tile size
  float depth;    // sanitized
  float jitter;   // of its samples
};

// Reads the pixel; false (centre.color alone set) when under kMinBlurPixels of blur reach its
// whole neighbourhood, so that the gather leaves it its own colour.
bool readGatherCentre(uvec2 pixel, uint index, out GatherCentre centre) {
  const uvec4 own = blurSampleAt(index);
  centre.color = sanitizeColor(vec4(sampleColor(own), 1.0));
  const vec4 dominant = neighborMaxAt((pixel.y / params.tileSize) * params.tilesX + pixel.x / params.tileSize);
  if (dominant.z < kMinBlurPixels) return false;
  centre.dominant = dominant.xy;
  gatherVelocity(sampleVelocity(own), params.velocityScale, float(params.tileSize), centre.speed);
  centre.depth = sanitizeDepth(sampleDepth(own));
  centre.jitter = unitFromHash(mblurHash(pixel.x, pixel.y, params.seed));
  return true;
}

// The blurred colour of `pixel`; the scales multiply w_f and w_b (the hybrid's mask boosts,
// else 1).
vec4 gatherSamples(uvec2 pixel, GatherCentre c, float foregroundScale, float backgroundScale) {
  const vec4 centreColor = c.color;
  const float centreSpeed = c.speed, centreDepth = c.depth, jitter = c.jitter;
  const vec2 dominant = c.dominant;
  const float maxSpeed = float(params.tileSize);
  const bool adapted = (params.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) != 0u;
  float weightSum = 1.0 / max(centreSpeed, 0.5);
  vec4 sum = centreColor * weightSum;

  const vec2 centre = vec2(pixel) + 0.5;
  const uint samples = params.samples;
  for (uint i = 0u; i < samples; ++i) {
    float t;
    if (adapted) {
      t = (float(i) + 1.0 - jitter) / float(samples);
    } else {
      if ((samples & 1u) == 1u && i == (samples - 1u) / 2u) continue;
      t = mix(-1.0, 1.0, (float(i) + jitter + 0.5) / float(samples + 1u));
    }
    const ivec2 samplePixel = nearestPixel(centre + t * dominant, params.width, params.height);
    const uint sampleIndex = uint(samplePixel.y) * params.width + uint(samplePixel.x);
    const float ds = length(vec2(samplePixel - ivec2(pixel)));
    const uvec4 packed = blurSampleAt(sampleIndex);
    float sampleSpeed;
    gatherVelocity(sampleVelocity(packed), params.velocityScale, maxSpeed, sampleSpeed);
    const float sampleDepth = sanitizeDepth(sampleDepth(packed));

    const float z = (centreDepth - sampleDepth) / params.softZExtent;
    float wf = clamp(1.0 + z, 0.0, 1.0) * cone(ds, sampleSpeed);
    float wb = clamp(1.0 - z, 0.0, 1.0) * cone(ds, centreSpeed);
    const float ws = cylinder(sampleSpeed, ds) * cylinder(centreSpeed, ds) * 2.0;
    if (centreDepth - sampleDepth >= params.softZExtent) wf *= params.foregroundBoost;
    wf *= foregroundScale;
    wb *= backgroundScale;
    const float w = wf + wb + ws;
    const vec4 sampleColor = sanitizeColor(vec4(sampleColor(packed), 1.0));
    weightSum += w;
    sum += w * contributionOf(sampleIndex, sampleColor);
  }
  return sum / weightSum;
}

#endif
