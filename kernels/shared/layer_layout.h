// An image layer (the G-buffer the resolve writes, the revealed layer the ray reveal writes),
// packed so that each reader takes what it needs in one or two 16-byte loads per pixel:
//   sample  (uvec4): x, y = linear RGB, 21 bits a channel (r in x's low bits, g across x's top
//                    11 and y's low 10, b above it), z = camera-space depth (float bits),
//                    w = velocity in half floats (x low, y high): all every gather reads of a
//                    sample (kernels/mblur/gather_samples.glsl), which takes only its length;
//   surface (uvec4): x = world normal (octahedral, snorm16 x 2), y = object id (0: the
//                    background, whose normal is 0), z = velocity in half floats (as the
//                    sample's), w = camera-space depth (float bits, as the sample's): what
//                    the ray mask, the composite's coverage test and the AOVs (but the
//                    velocity's) read. The mask's tests of an object boundary (paper, eqs. 1,
//                    2: another object, deeper) take a pixel's id and depth in one load (with
//                    the depth only in the sample, the hybrid's tile-max took longer:
//                    bench/results/surface-depth/).
// Beside a G-buffer's records, its velocities (vec2 per pixel: the velocity as floats, a
// non-finite one written as none; whole 16-byte records, an entry past an odd pixel count
// unused): what tile-max ranks, so that each tile takes the direction of its fastest pixel where
// the half floats would make near-equal speeds tie or swap (bench/results/tile-max-ranking/),
// and the velocity AOV. The hybrid's revealed layer, which no tile-max reads, has none.
// Velocity is pixels per frame, y down; a non-finite one is written as none (in halves, a step
// of 1/32 pixel at 40 pixels, and the direction kept past the largest half). A
// colour channel (alpha is 1 everywhere) is a float's top 21 bits: 13 mantissa bits, rounded, so
// within 2^-14 (6.1e-5) of the value relative; negative, subnormal and NaN values are written as
// 0, values past HMB_LAYER_MAX_COLOR as it. Depth is kept bit for bit (readers sanitize it).
// On lavapipe every access at a per-pixel address is a loop over the lanes, whatever its width,
// so two stores per pixel and one load per gather sample replace four and three; on GPUs the
// layer takes 32 bytes per pixel instead of 44.
//
// The functions below are shared with the host (readbacks, tests' inputs and references), so
// both sides round the same way. The layer's two buffers take 2 binding numbers
// (shared/layer_bindings.glsl), or one table of their addresses on devices with few bindings.
#ifndef HMB_KERNELS_SHARED_LAYER_LAYOUT_H
#define HMB_KERNELS_SHARED_LAYER_LAYOUT_H

#include "glsl_cpp.h"

#ifdef HMB_ADDRESS_TABLES
#ifndef __cplusplus
layout(buffer_reference, std430, buffer_reference_align = 16) buffer LayerTexelsRef { uvec4 v[]; };
#endif

HMB_GPU_BEGIN

struct LayerTable {
  HMB_REFERENCE(LayerTexelsRef) samples;
  HMB_REFERENCE(LayerTexelsRef) surfaces;
};

HMB_GPU_END

HMB_CHECK_SIZE(LayerTable, 16)
#endif

#define HMB_LAYER_BINDINGS 2
// A G-buffer's velocities for `pixels` pixels: entries, rounded up to whole 16-byte records.
#define HMB_LAYER_VELOCITY_ENTRIES(pixels) (((pixels) + 1u) / 2u * 2u)

HMB_GPU_BEGIN

// The largest finite half float: the sample's velocity keeps within it.
const float kLayerHalfMax = 65504.0f;
// The brightest colour a layer holds: the gathers clamp to the same (HMB_MBLUR_MAX_COLOR).
#define HMB_LAYER_MAX_COLOR 65504.0f
// The least normal float: smaller magnitudes pack as 0, as devices that flush subnormals see them.
const float kLayerLeastNormal = 1.17549435e-38f;

// A colour channel as 21 bits: its float's bits without the sign and the 10 lowest mantissa
// bits, rounded to nearest (a carry moves into the exponent, as it should).
HMB_SHARED uint packColorChannel(float c) {
  return c >= kLayerLeastNormal ? (floatBitsToUint(min(c, HMB_LAYER_MAX_COLOR)) + 0x200u) >> 10u : 0u;
}
HMB_SHARED float unpackColorChannel(uint bits21) { return uintBitsToFloat(bits21 << 10u); }

// Non-finite velocities are no motion; one too long for a half keeps its direction.
HMB_SHARED uint packLayerVelocity(vec2 v) {
  if (isnan(v.x) || isnan(v.y) || isinf(v.x) || isinf(v.y)) return 0u;
  const float largest = max(abs(v.x), abs(v.y));
  if (largest > kLayerHalfMax) v = v * (kLayerHalfMax / largest);
  return packHalf2x16(v);
}

HMB_SHARED float layerSignNotZero(float x) { return x >= 0.0f ? 1.0f : -1.0f; }

// Octahedral encoding (Meyer et al. 2010): the unit sphere folded onto a square, each axis in 16
// bits (about 1e-4 radians at worst). A zero (or subnormal) or non-finite normal packs as +z.
HMB_SHARED uint packOctahedral(vec3 n) {
  const float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  if (!(l1 >= kLayerLeastNormal) || isinf(l1)) return packSnorm2x16(vec2(0.0f, 0.0f));
  vec2 p = vec2(n.x, n.y) / l1;
  if (n.z < 0.0f)
    p = vec2((1.0f - abs(p.y)) * layerSignNotZero(p.x), (1.0f - abs(p.x)) * layerSignNotZero(p.y));
  return packSnorm2x16(p);
}

HMB_SHARED vec3 unpackOctahedral(uint word) {
  const vec2 e = unpackSnorm2x16(word);
  vec3 v = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
  if (v.z < 0.0f) {
    const float x = v.x;
    v.x = (1.0f - abs(v.y)) * layerSignNotZero(x);
    v.y = (1.0f - abs(x)) * layerSignNotZero(v.y);
  }
  return normalize(v);
}

HMB_SHARED uvec4 packLayerSample(vec3 color, float depth, vec2 velocity) {
  const uint r = packColorChannel(color.x), g = packColorChannel(color.y), b = packColorChannel(color.z);
  return uvec4(r | (g << 21u), (g >> 11u) | (b << 10u), floatBitsToUint(depth), packLayerVelocity(velocity));
}

HMB_SHARED uvec4 packLayerSurface(vec3 normal, uint objectId, float depth, vec2 velocity) {
  return uvec4(packOctahedral(normal), objectId, packLayerVelocity(velocity), floatBitsToUint(depth));
}

// A G-buffer's velocities entry.
HMB_SHARED vec2 layerVelocityEntry(vec2 v) {
  return (isnan(v.x) || isnan(v.y) || isinf(v.x) || isinf(v.y)) ? vec2(0.0f) : v;
}

// Of a sample.
HMB_SHARED vec3 sampleColor(uvec4 blurSample) {
  const uint r = blurSample.x & 0x1FFFFFu, g = (blurSample.x >> 21u) | ((blurSample.y & 0x3FFu) << 11u),
             b = (blurSample.y >> 10u) & 0x1FFFFFu;
  return vec3(unpackColorChannel(r), unpackColorChannel(g), unpackColorChannel(b));
}
HMB_SHARED float sampleDepth(uvec4 blurSample) { return uintBitsToFloat(blurSample.z); }
HMB_SHARED vec2 sampleVelocity(uvec4 blurSample) { return unpackHalf2x16(blurSample.w); }
// Of a surface.
HMB_SHARED uint surfaceObjectId(uvec4 surface) { return surface.y; }
HMB_SHARED vec3 surfaceNormal(uvec4 surface) { return surface.y == 0u ? vec3(0.0f) : unpackOctahedral(surface.x); }
HMB_SHARED vec2 surfaceVelocity(uvec4 surface) { return unpackHalf2x16(surface.z); }
HMB_SHARED float surfaceDepth(uvec4 surface) { return uintBitsToFloat(surface.w); }

HMB_GPU_END

#endif
