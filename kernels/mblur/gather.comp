#version 450
// Reconstruction gather of McGuire et al. 2012 ("A Reconstruction Filter for Plausible Motion
// Blur", I3D 2012) with the weights of the paper's appendix (eqs. 5-10):
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
// for 1/|v| of the exposure; 0.5 px bounds the weight of still pixels at 2).
//
// The paper's section 4 heuristics: w_f is multiplied by foregroundBoost when the pixel is
// deeper than the sample by at least SOFT_Z_EXTENT (x30 for the adapted range). With the mask
// flag, pixels in the mask multiply w_b by maskBackgroundBoost and divide w_f by
// maskForegroundDivide (x3 and /3 in the paper), so that revealed background shows through the
// silhouettes of foreground objects; the hybrid method runs this same kernel on its raster and
// revealed layers.
//
// The hybrid composite (paper, section 3: both layers blurred, then composited; the paper
// leaves the form open). At a mask pixel X the raster holds the moving object, and the samples
// the gather takes behind X (other objects deeper than X) are the wrong background: what lies
// beyond the silhouette, not behind X. The background layer (the raster with the revealed
// surfaces written in at mask pixels), blurred by this kernel in pixel-list mode, gives B, the
// right background at X. Two forms:
//  - weights: each sample's colour becomes mix(c_s, B, b), b its share behind X, inside the
//    usual weighted sum, with the mask boosts (x3 background, /3 foreground) as in the paper.
//  - coverage (default): under the linear-motion convention X is covered by its object at
//    shutter fraction s exactly when X + (1 - s) v_X lies on that object now, so the share of
//    samples X + u v_X, u in (0, 1], that are on it (or not behind X) estimates the coverage
//    alpha, and the object's blurred colour F is the plain mean of those samples (and X):
//    C = alpha F + (1 - alpha) B. v_X is the pixel's own velocity, clamped only to the image
//    (coverageMaxSpeed), not to the tile: a fast object's inner blur is as wide as its motion
//    even where the gather's tiles clamp its outer blur. The README gives the measured errors.
#extension GL_GOOGLE_include_directive : require
#include "mblur_layout.h"
#include "../hybrid/hybrid_layout.h"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;

layout(std430, binding = HMB_GATHER_BINDING_COLOR) readonly buffer Color { vec4 baseColor[]; };
layout(std430, binding = HMB_GATHER_BINDING_NORMAL_DEPTH) readonly buffer NormalDepth { vec4 baseNormalDepth[]; };
layout(std430, binding = HMB_GATHER_BINDING_VELOCITY) readonly buffer Velocity { vec2 baseVelocity[]; };
layout(std430, binding = HMB_GATHER_BINDING_NEIGHBOR_MAX) readonly buffer NeighborMax { vec4 neighborMax[]; };
layout(std430, binding = HMB_GATHER_BINDING_MASK) readonly buffer Mask { uint mask[]; };
layout(std430, binding = HMB_GATHER_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };
layout(std430, binding = HMB_GATHER_BINDING_LIST) readonly buffer List { uint pixelList[]; };
layout(std430, binding = HMB_GATHER_BINDING_LIST_LENGTH) readonly buffer ListLength { uint listLength; };
layout(std430, binding = HMB_GATHER_BINDING_BACKGROUND) readonly buffer Background { vec4 background[]; };
layout(std430, binding = HMB_GATHER_BINDING_OBJECT_ID) readonly buffer ObjectId { uint objectId[]; };
layout(std430, binding = HMB_GATHER_BINDING_OVERLAY_COLOR) readonly buffer OverlayColor { vec4 overlayColor[]; };
layout(std430, binding = HMB_GATHER_BINDING_OVERLAY_NORMAL_DEPTH) readonly buffer OverlayNormalDepth {
  vec4 overlayNormalDepth[];
};
layout(std430, binding = HMB_GATHER_BINDING_OVERLAY_VELOCITY) readonly buffer OverlayVelocity { vec2 overlayVelocity[]; };
layout(push_constant) uniform Params { GatherParams params; };

#include "mblur_common.glsl"

// The layer at pixel i: its own buffers, or the overlay's where the overlay flag and mask say.
bool overlaid(uint i) { return (params.flags & HMB_GATHER_FLAG_OVERLAY) != 0u && mask[i] == HMB_MASK_REVEALED; }
vec4 layerColor(uint i) { return overlaid(i) ? overlayColor[i] : baseColor[i]; }
float layerDepth(uint i) { return overlaid(i) ? overlayNormalDepth[i].w : baseNormalDepth[i].w; }
vec2 layerVelocity(uint i) { return overlaid(i) ? overlayVelocity[i] : baseVelocity[i]; }

// Share of sample `sampleIndex` that is background to the pixel (object `centreObject` at
// `centreDepth`).
float behindShare(uint sampleIndex, uint centreObject, float centreDepth) {
  return behindShareOf(objectId[sampleIndex], sanitizeDepth(layerDepth(sampleIndex)), centreObject, centreDepth,
                       params.softZExtent);
}

// The coverage composite at a mask pixel (see above).
vec4 coverageComposite(uvec2 pixel, uint index, vec4 centreColor, float centreDepth, float jitter) {
  float speed;
  const vec2 v = gatherVelocity(layerVelocity(index), params.velocityScale, params.coverageMaxSpeed, speed);
  const uint centreObject = objectId[index];
  vec4 foregroundSum = centreColor;
  float foregroundCount = 0.0;
  for (uint i = 0u; i < params.samples; ++i) {
    const ivec2 samplePixel = coverageSamplePixel(pixel, v, i, params.samples, jitter, params.width, params.height);
    const uint sampleIndex = uint(samplePixel.y) * params.width + uint(samplePixel.x);
    const float onObject = 1.0 - behindShare(sampleIndex, centreObject, centreDepth);
    foregroundSum += onObject * sanitizeColor(layerColor(sampleIndex));
    foregroundCount += onObject;
  }
  const float alpha = foregroundCount / float(params.samples);
  // alpha is exactly 1 where no sample is behind: range_check leaves those pixels unrevealed
  // (their background entry is stale, and sanitized, then weighted by exactly 0).
  return alpha * (foregroundSum / (1.0 + foregroundCount)) + (1.0 - alpha) * sanitizeColor(background[index]);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if ((params.flags & HMB_GATHER_FLAG_PIXEL_LIST) != 0u) {
    const uint entry = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * (HMB_GATHER_GROUP_X * HMB_GATHER_GROUP_Y) +
                       gl_LocalInvocationID.y * HMB_GATHER_GROUP_X + gl_LocalInvocationID.x;
    if (entry >= listLength) return;
    const uint listed = pixelList[entry];
    pixel = uvec2(listed % params.width, listed / params.width);
  }
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const vec4 centreColor = sanitizeColor(layerColor(index));

  const vec4 dominant = neighborMax[(pixel.y / params.tileSize) * params.tilesX + pixel.x / params.tileSize];
  if (dominant.z < 0.5) {  // under half a pixel of blur in the whole neighbourhood
    outColor[index] = centreColor;
    return;
  }

  const float maxSpeed = float(params.tileSize);
  float centreSpeed;
  gatherVelocity(layerVelocity(index), params.velocityScale, maxSpeed, centreSpeed);
  const float centreDepth = sanitizeDepth(layerDepth(index));
  const bool adapted = (params.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) != 0u;
  const bool inMask = (params.flags & HMB_GATHER_FLAG_USE_MASK) != 0u && mask[index] != 0u;  // boosts, composite
  const float backgroundScale = inMask ? params.maskBackgroundBoost : 1.0;
  const float foregroundScale = inMask ? 1.0 / params.maskForegroundDivide : 1.0;
  const float jitter = unitFromHash(mblurHash(pixel.x, pixel.y, params.seed));
  if (inMask && (params.flags & HMB_GATHER_FLAG_COMPOSITE_COVERAGE) != 0u) {
    outColor[index] = coverageComposite(pixel, index, centreColor, centreDepth, jitter);
    return;
  }
  const bool compositeWeights = inMask && (params.flags & HMB_GATHER_FLAG_COMPOSITE_WEIGHTS) != 0u;
  const vec4 revealed = compositeWeights ? sanitizeColor(background[index]) : vec4(0.0);
  const uint centreObject = compositeWeights ? objectId[index] : 0u;

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
    const ivec2 samplePixel = nearestPixel(centre + t * dominant.xy, params.width, params.height);
    const uint sampleIndex = uint(samplePixel.y) * params.width + uint(samplePixel.x);
    const float ds = length(vec2(samplePixel - ivec2(pixel)));
    float sampleSpeed;
    gatherVelocity(layerVelocity(sampleIndex), params.velocityScale, maxSpeed, sampleSpeed);
    const float sampleDepth = sanitizeDepth(layerDepth(sampleIndex));

    const float z = (centreDepth - sampleDepth) / params.softZExtent;
    float wf = clamp(1.0 + z, 0.0, 1.0) * cone(ds, sampleSpeed);
    float wb = clamp(1.0 - z, 0.0, 1.0) * cone(ds, centreSpeed);
    const float ws = cylinder(sampleSpeed, ds) * cylinder(centreSpeed, ds) * 2.0;
    if (centreDepth - sampleDepth >= params.softZExtent) wf *= params.foregroundBoost;
    wf *= foregroundScale;
    wb *= backgroundScale;
    const float w = wf + wb + ws;
    const vec4 sampleColor = sanitizeColor(layerColor(sampleIndex));
    weightSum += w;
    sum += w * (compositeWeights ? mix(sampleColor, revealed, behindShare(sampleIndex, centreObject, centreDepth))
                                 : sampleColor);
  }
  outColor[index] = sum / weightSum;
}
