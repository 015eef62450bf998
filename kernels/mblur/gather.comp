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
#extension GL_GOOGLE_include_directive : require
#include "mblur_layout.h"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;

layout(std430, binding = HMB_GATHER_BINDING_COLOR) readonly buffer Color { vec4 color[]; };
layout(std430, binding = HMB_GATHER_BINDING_NORMAL_DEPTH) readonly buffer NormalDepth { vec4 normalDepth[]; };
layout(std430, binding = HMB_GATHER_BINDING_VELOCITY) readonly buffer Velocity { vec2 velocity[]; };
layout(std430, binding = HMB_GATHER_BINDING_NEIGHBOR_MAX) readonly buffer NeighborMax { vec4 neighborMax[]; };
layout(std430, binding = HMB_GATHER_BINDING_MASK) readonly buffer Mask { uint mask[]; };
layout(std430, binding = HMB_GATHER_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };
layout(push_constant) uniform Params { GatherParams params; };

#include "mblur_common.glsl"

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const vec4 centreColor = sanitizeColor(color[index]);

  const vec4 dominant = neighborMax[(pixel.y / params.tileSize) * params.tilesX + pixel.x / params.tileSize];
  if (dominant.z < 0.5) {  // under half a pixel of blur in the whole neighbourhood
    outColor[index] = centreColor;
    return;
  }

  const float maxSpeed = float(params.tileSize);
  float centreSpeed;
  gatherVelocity(velocity[index], params.velocityScale, maxSpeed, centreSpeed);
  const float centreDepth = sanitizeDepth(normalDepth[index].w);
  const bool adapted = (params.flags & HMB_GATHER_FLAG_ADAPTED_RANGE) != 0u;
  const bool inMask = (params.flags & HMB_GATHER_FLAG_USE_MASK) != 0u && mask[index] != 0u;
  const float backgroundScale = inMask ? params.maskBackgroundBoost : 1.0;
  const float foregroundScale = inMask ? 1.0 / params.maskForegroundDivide : 1.0;

  float weightSum = 1.0 / max(centreSpeed, 0.5);
  vec4 sum = centreColor * weightSum;

  const float jitter = unitFromHash(mblurHash(pixel.x, pixel.y, params.seed));
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
    gatherVelocity(velocity[sampleIndex], params.velocityScale, maxSpeed, sampleSpeed);
    const float sampleDepth = sanitizeDepth(normalDepth[sampleIndex].w);

    const float z = (centreDepth - sampleDepth) / params.softZExtent;
    float wf = clamp(1.0 + z, 0.0, 1.0) * cone(ds, sampleSpeed);
    float wb = clamp(1.0 - z, 0.0, 1.0) * cone(ds, centreSpeed);
    const float ws = cylinder(sampleSpeed, ds) * cylinder(centreSpeed, ds) * 2.0;
    if (centreDepth - sampleDepth >= params.softZExtent) wf *= params.foregroundBoost;
    wf *= foregroundScale;
    wb *= backgroundScale;
    const float w = wf + wb + ws;
    weightSum += w;
    sum += w * sanitizeColor(color[sampleIndex]);
  }
  outColor[index] = sum / weightSum;
}
