#version 450
// Motion blur gather after Jimenez 2014, "Next Generation Post Processing in Call of Duty:
// Advanced Warfare" (SIGGRAPH 2014 Advances in Real-Time Rendering in Games course): the
// filter UE4's motion blur follows, the paper's third baseline. From the course notes:
//  - velocities as centred blur radii (half the per-exposure displacement), clamped to the
//    tile size; tile-max and neighbour-max are the McGuire passes (tile_max, neighbor_max) run
//    with that conversion and this filter's tile size;
//  - the neighbour-max lookup is jittered per pixel (up to +-tileJitter tiles per axis), which
//    turns the blocky tile boundaries into noise;
//  - samples come in mirrored pairs X +- t v_N, t = (k + 1 - r) / P in (0, 1], k < P pairs;
//  - each sample's weight compares depth softly (a 0.5-centred ramp over SOFT_Z_EXTENT that
//    splits it into behind / in front) and compares spreads in sample units (a sample behind
//    counts where the pixel's own blur reaches it, a sample in front where its blur reaches the
//    pixel): w = behind * spread(pixel) + front * spread(sample), w in [0, 1];
//  - mirror: when one sample of a pair lies behind the other and the other spreads further, the
//    one behind takes the other's weight, so background next to a blurred silhouette stands in
//    for the background the foreground hides;
//  - weights are coverage: the pixel's own colour fills what the 2P samples leave,
//    result = (sum w c + (2P - sum w) c_X) / 2P.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "filter_bindings.glsl"

layout(local_size_x = HMB_GATHER_GROUP_X, local_size_y = HMB_GATHER_GROUP_Y) in;
layout(push_constant) uniform Params { JimenezParams params; };

#include "mblur_common.glsl"

// Soft depth comparison: x = how much the sample lies behind the pixel, y = in front; x + y = 1.
vec2 depthCompare(float centreDepth, float sampleDepth) {
  const float d = (sampleDepth - centreDepth) / params.softZExtent;
  return clamp(vec2(0.5 + d, 0.5 - d), 0.0, 1.0);
}

// 1 where a blur of `spread` sample units reaches `offset` sample units away, fading over one.
float spreadCompare(float offset, float spread) { return clamp(spread - max(offset - 1.0, 0.0), 0.0, 1.0); }

float sampleWeight(float centreDepth, float sampleDepth, float offset, float centreSpread, float sampleSpread) {
  const vec2 depth = depthCompare(centreDepth, sampleDepth);
  return depth.x * spreadCompare(offset, centreSpread) + depth.y * spreadCompare(offset, sampleSpread);
}

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const uvec4 own = layerSampleAt(index);
  const vec4 centreColor = sanitizeColor(vec4(sampleColor(own), 1.0));

  uint h = mblurHash(pixel.x, pixel.y, params.seed);
  const float sampleJitter = unitFromHash(h);
  h = nextHash(h);
  const float jitterX = unitFromHash(h);
  h = nextHash(h);
  const float jitterY = unitFromHash(h);
  const vec2 centre = vec2(pixel) + 0.5;
  const float m = float(params.tileSize);
  const vec2 lookup = centre / m + (vec2(jitterX, jitterY) * 2.0 - 1.0) * params.tileJitter;
  const ivec2 tile = clamp(ivec2(floor(lookup)), ivec2(0), ivec2(params.tilesX, params.tilesY) - 1);
  const vec4 dominant = neighborMaxAt(uint(tile.y) * params.tilesX + uint(tile.x));
  if (dominant.z < kMinBlurPixels) {
    outColor[index] = centreColor;
    return;
  }

  const uint pairs = (params.samples + 1u) / 2u;
  const float pixelsToSampleUnits = float(pairs) / dominant.z;
  float centreSpeed;
  gatherVelocity(sampleVelocity(own), params.velocityScale, m, centreSpeed);
  const float centreSpread = centreSpeed * pixelsToSampleUnits;
  const float centreDepth = sanitizeDepth(sampleDepth(own));

  vec4 sum = vec4(0.0);
  float weightSum = 0.0;
  for (uint k = 0u; k < pairs; ++k) {
    const float offset = float(k) + 1.0 - sampleJitter;  // sample units
    const vec2 step = (offset / float(pairs)) * dominant.xy;
    const ivec2 pixelA = nearestPixel(centre + step, params.width, params.height);
    const ivec2 pixelB = nearestPixel(centre - step, params.width, params.height);
    const uint indexA = uint(pixelA.y) * params.width + uint(pixelA.x);
    const uint indexB = uint(pixelB.y) * params.width + uint(pixelB.x);
    const uvec4 sampleA = layerSampleAt(indexA), sampleB = layerSampleAt(indexB);
    float speedA, speedB;
    gatherVelocity(sampleVelocity(sampleA), params.velocityScale, m, speedA);
    gatherVelocity(sampleVelocity(sampleB), params.velocityScale, m, speedB);
    const float depthA = sanitizeDepth(sampleDepth(sampleA));
    const float depthB = sanitizeDepth(sampleDepth(sampleB));
    const float spreadA = speedA * pixelsToSampleUnits, spreadB = speedB * pixelsToSampleUnits;
    float weightA = sampleWeight(centreDepth, depthA, offset, centreSpread, spreadA);
    float weightB = sampleWeight(centreDepth, depthB, offset, centreSpread, spreadB);
    if (depthA > depthB && spreadB > spreadA) {
      weightA = weightB;
    } else if (depthB > depthA && spreadA > spreadB) {
      weightB = weightA;
    }
    sum += weightA * sanitizeColor(vec4(sampleColor(sampleA), 1.0)) + weightB * sanitizeColor(vec4(sampleColor(sampleB), 1.0));
    weightSum += weightA + weightB;
  }
  const float sampleCount = float(2u * pairs);
  outColor[index] = (sum + max(sampleCount - weightSum, 0.0) * centreColor) / sampleCount;
}
