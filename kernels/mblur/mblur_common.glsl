// Functions every motion blur kernel shares; the C++ reference (tests/mblur/mblur_reference.cpp)
// mirrors each one. Include after mblur_layout.h.
#ifndef HMB_KERNELS_MBLUR_MBLUR_COMMON_GLSL
#define HMB_KERNELS_MBLUR_MBLUR_COMMON_GLSL

#include "mblur_hash.h"

// G-buffer velocity q (pixels per frame) -> the velocity a gather uses (pixels per exposure,
// halved for a centred range: velocityScale says which), its length clamped to maxSpeed.
// `speed` is min(|v|, maxSpeed), the ranking key of the tile passes. Non-finite velocities, and
// ones too large to scale, count as zero; so do speeds under 1e-30 px (no device agrees on
// denormals). The length is taken after dividing by the largest component, so 1e30 px per
// frame clamps to maxSpeed instead of overflowing to a zero-length vector. Also in two steps
// (gatherVelocityParts, then clampedGatherVelocity), so that one velocity can be clamped to two
// lengths for the cost of one and a division (the hybrid's tile-max: to the tile for the
// reduction, to the image for eqs. 1, 2), the same bits as gatherVelocity gives for each.
struct GatherVelocityParts {
  vec2 v;           // q scaled
  vec2 unit;        // v over its largest component
  float unitLength;
  float fullSpeed;  // |v|; 0 for no motion (non-finite, or under 1e-30 px)
};
GatherVelocityParts gatherVelocityParts(vec2 q, float velocityScale) {
  GatherVelocityParts p;
  p.v = q * velocityScale;
  p.unit = vec2(0.0);
  p.unitLength = 1.0;
  p.fullSpeed = 0.0;
  if (any(isnan(p.v)) || any(isinf(p.v))) return p;
  const float largest = max(abs(p.v.x), abs(p.v.y));
  if (!(largest >= 1e-30)) return p;
  p.unit = p.v / largest;  // the largest component is +-1
  p.unitLength = length(p.unit);
  p.fullSpeed = largest * p.unitLength;
  return p;
}
vec2 clampedGatherVelocity(GatherVelocityParts p, float maxSpeed, out float speed) {
  speed = min(p.fullSpeed, maxSpeed);
  if (!(p.fullSpeed > 0.0)) return vec2(0.0);
  return p.fullSpeed <= maxSpeed ? p.v : p.unit * (maxSpeed / p.unitLength);
}
vec2 gatherVelocity(vec2 q, float velocityScale, float maxSpeed, out float speed) {
  return clampedGatherVelocity(gatherVelocityParts(q, velocityScale), maxSpeed, speed);
}

// gatherVelocity's speed alone, all the gathers' weights read of a velocity: min(|v|, maxSpeed),
// 0 for non-finite velocities and speeds under 1e-30 px. |v| is sqrt(x^2 + y^2), without the
// overflow guard's two divisions, which held up every sample: a square that overflows gives an
// infinite |v|, clamped to maxSpeed as gatherVelocity clamps it, and one that underflows gives
// 0, which every weight treats as it treats a speed under 1e-30 (within a ulp of gatherVelocity's).
float gatherSpeed(vec2 q, float velocityScale, float maxSpeed) {
  const vec2 v = q * velocityScale;
  if (any(isnan(v)) || any(isinf(v))) return 0.0;
  const float speed = min(length(v), maxSpeed);
  return speed >= 1e-30 ? speed : 0.0;
}

// Inputs are sanitized so that no NaN or Inf can reach a weighted sum.
float sanitizeChannel(float x) { return isnan(x) ? 0.0 : clamp(x, -HMB_MBLUR_MAX_COLOR, HMB_MBLUR_MAX_COLOR); }

vec4 sanitizeColor(vec4 c) {
  return vec4(sanitizeChannel(c.x), sanitizeChannel(c.y), sanitizeChannel(c.z), sanitizeChannel(c.w));
}

float sanitizeDepth(float z) { return isnan(z) ? HMB_MBLUR_MAX_DEPTH : clamp(z, 0.0, HMB_MBLUR_MAX_DEPTH); }

// Nearest pixel to a position (pixel centres at integer + 0.5), clamped to the image.
ivec2 nearestPixel(vec2 position, uint width, uint height) {
  return clamp(ivec2(floor(position)), ivec2(0), ivec2(int(width) - 1, int(height) - 1));
}

// Share of a sample that is background to a pixel (the hybrid composite): none on the pixel's
// own object, else saturate((z_s - z_t) / SOFT_Z_EXTENT). Depths already sanitized.
float behindShareOf(uint sampleObject, float sampleDepth, uint centreObject, float centreDepth, float softZExtent) {
  if (sampleObject == centreObject) return 0.0;
  return clamp((sampleDepth - centreDepth) / softZExtent, 0.0, 1.0);
}

// The coverage composite's sample i of `samples` along the pixel's own path X + u v + u^2 q
// (q = 0: the straight displacement v; else the curved path's terms, inversePath): the same
// positions in reveal/composite.comp (which blends) and range_check.comp (which decides whether
// the pixel needs the revealed background at all). `precise`: the two kernels are compiled
// apart, and a fused multiply-add in one but not the other could move a sample across a pixel
// border, listing a pixel for the reveal whose composite then reads no background or the reverse.
ivec2 coverageSamplePixel(uvec2 pixel, vec2 v, vec2 q, uint i, uint samples, float jitter, uint width, uint height) {
  precise const float u = (float(i) + 1.0 - jitter) / float(samples);
  precise const vec2 position = vec2(pixel) + 0.5 + u * v + (u * u) * q;
  return nearestPixel(position, width, height);
}

// The curved path (mblur/gather_samples.glsl): a path record's terms, its point's path
// p(t - uE) = X - u a - u^2 c through its points at mid-shutter and shutter open
// (gbuffer/gbuffer_layout.h: m = X - p(t - E/2), o = X - p(t - E)), so a = 4m - o, c = 2o - 4m.
// False for a record without a path.
bool shutterPathTerms(uvec2 record, out vec2 a, out vec2 c) {
  const vec2 m = unpackHalf2x16(record.x), o = unpackHalf2x16(record.y);
  precise const vec2 linear = 4.0 * m - o, quadratic = 2.0 * o - 4.0 * m;  // precise: see inversePath
  a = linear;
  c = quadratic;
  return !(any(isnan(m)) || any(isnan(o)) || any(isinf(m)) || any(isinf(o)));
}

// The path along which pixel X sees the points of its own surface over the shutter,
// X + u linear + u^2 quadratic: to second order X + u a + u^2 (c + J_a a), where J_a a
// (`change`) is approximated by the frame velocity at X + a minus X's, scaled to the exposure, when X + a
// lies on X's surface (else 0). Scaled so that |linear| + |quadratic|, which bounds the path's
// reach, stays within maxLength; the lengths are taken over the largest component, so a
// change of 1e30 px clamps instead of overflowing to an infinite reach (and a zero path).
float overflowFreeLength(vec2 x) {
  const float largest = max(abs(x.x), abs(x.y));
  return largest > 0.0 ? largest * length(x / largest) : 0.0;
}

// `precise` for the same reason as coverageSamplePixel's: both kernels must find the same path.
void inversePath(vec2 a, vec2 c, vec2 change, float maxLength, out vec2 linear, out vec2 quadratic) {
  precise const vec2 k = any(isnan(change)) || any(isinf(change)) ? c : c + change;
  precise const float reach = overflowFreeLength(a) + overflowFreeLength(k);
  precise const float scale = reach > maxLength ? maxLength / reach : 1.0;
  linear = a * scale;
  quadratic = k * scale;
}

// Paper eq. 6/7's speed falloff saturate(1 - ds / v); a zero speed reaches only ds = 0.
float cone(float ds, float v) { return clamp(1.0 - ds / max(v, 1e-6), 0.0, 1.0); }

// Paper eq. 10: 1 - smoothstep(0.95 v, 1.05 v, s), written out because smoothstep is undefined
// for equal edges (v = 0).
float cylinder(float v, float s) {
  if (v <= 0.0) return s <= 0.0 ? 1.0 : 0.0;
  const float t = clamp((s - 0.95 * v) / (0.1 * v), 0.0, 1.0);
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

#endif
