#version 450
// Ray mask, second pass (paper, eqs. 3, 4): an edge candidate (eqs. 1, 2 hold: listed by
// tile_max_edge_candidates) enters the edge mask when the 5x5 Sobel of depth and normal around it passes the
// edge threshold e:
//   x = delta_d + delta_n, x_n = saturate(1 - 1 / (x + 1)), edge when x_n > e.
// delta_d is the Sobel gradient's length of depth divided by the pixel's own depth: a
// relative depth step, so the same threshold marks the same silhouettes whether the scene is
// modelled in millimetres or kilometres. delta_n is the length of the normal's Sobel
// derivatives (both directions, all three components). Image borders clamp. Writes 1 at edge
// pixels, and at the coarse mask's blocks near them, only; the edge buffer is filled with 0
// before.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "ray_mask_layout.h"
#include "../mblur/mblur_layout.h"
#include "../shared/indexing.glsl"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_MASK_LIST_GROUP) in;

// The G-buffer's surfaces (normal, depth: shared/layer_layout.h), read at per-pixel addresses as
// a uniform texel buffer (one record a pixel: shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_EDGE_MASK_BINDING_SURFACES) uniform utextureBuffer surfaceTexels;
uvec4 surfaceAt(uint i) { return recordAt(surfaceTexels, i); }
layout(std430, binding = HMB_EDGE_MASK_BINDING_COUNTERS) readonly buffer Counters { RayMaskCounters counters; };
layout(std430, binding = HMB_EDGE_MASK_BINDING_CANDIDATES) readonly buffer Candidates { uint candidates[]; };
// The edge mask, then the coarse one (HMB_EDGE_BLOCKS_FIRST).
layout(std430, binding = HMB_EDGE_MASK_BINDING_EDGES) buffer Edges { uint edges[]; };  // bits set by atomicOr
layout(push_constant) uniform Params { RayMaskParams params; };

#include "../mblur/mblur_common.glsl"
#include "ray_mask_common.glsl"

vec3 sanitizeNormal(vec3 n) { return any(isnan(n)) || any(isinf(n)) ? vec3(0.0) : clamp(n, vec3(-1.0), vec3(1.0)); }

// Eq. 3's x at the pixel. Depths enter relative to the window's largest, so no sum overflows
// (a far plane of 1e30 or a NaN read as the farthest depth is still an edge, and a scene
// modelled at 1e20 units is measured as one at 1).
float edgeStrength(ivec2 pixel, float depthHere) {
  const ivec2 last = ivec2(int(params.blur.width) - 1, int(params.blur.height) - 1);
  vec4 window[25];
  float largest = 0.0;
  for (int k = 0; k < 25; ++k) {
    const ivec2 p = clamp(pixel + ivec2(k % 5 - 2, k / 5 - 2), ivec2(0), last);
    const uint at = uint(p.y) * params.blur.width + uint(p.x);
    const uvec4 surface = surfaceAt(at);
    window[k] = vec4(sanitizeNormal(surfaceNormal(surface)), sanitizeDepth(surfaceDepth(surface)));
    largest = max(largest, window[k].w);
  }
  vec2 depthGradient = vec2(0.0);
  vec3 normalX = vec3(0.0), normalY = vec3(0.0);
  for (int k = 0; k < 25; ++k) {
    const int dx = k % 5 - 2, dy = k / 5 - 2;
    const float wx = sobelDerivative(dx) * sobelSmooth(dy);
    const float wy = sobelSmooth(dx) * sobelDerivative(dy);
    if (largest > 0.0) depthGradient += vec2(wx, wy) * (window[k].w / largest);
    normalX += wx * window[k].xyz;
    normalY += wy * window[k].xyz;
  }
  const float gradient = length(depthGradient);
  const float deltaD = gradient > 0.0 ? gradient * (largest / max(depthHere, 1e-30)) : 0.0;
  const float deltaN = sqrt(dot(normalX, normalX) + dot(normalY, normalY));
  return deltaD + deltaN;
}

void main() {
  const uint entry = linearInvocationIndex(HMB_MASK_LIST_GROUP);
  if (entry >= counters.candidateCount) return;
  const uint index = candidates[entry];
  const uvec2 pixel = uvec2(index % params.blur.width, index / params.blur.width);
  const float depthHere = sanitizeDepth(surfaceDepth(surfaceAt(index)));
  if (!(normalizedEdge(edgeStrength(ivec2(pixel), depthHere)) > params.edgeThreshold)) return;
  atomicOr(edges[index / 32u], 1u << (index % 32u));
  // Flag every block within one pixel of this one, in both forms of the coarse mask.
  const uvec2 first = uvec2(max(ivec2(pixel) - 1, ivec2(0))) / HMB_EDGE_BLOCK;
  const uvec2 last = min(pixel + 1u, uvec2(params.blur.width, params.blur.height) - 1u) / HMB_EDGE_BLOCK;
  for (uint y = first.y; y <= last.y; ++y)
    for (uint x = first.x; x <= last.x; ++x) {
      edges[HMB_EDGE_BLOCK_ENTRY(params.blur.width, params.blur.height, x, y)] = 1u;
      atomicOr(edges[HMB_EDGE_BLOCK_WORD(params.blur.width, params.blur.height, x, y)], 1u << (x % 32u));
    }
}
