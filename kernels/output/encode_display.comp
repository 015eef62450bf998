#version 450
// The display transform (design: metrics and PNGs use it): non-finite -> 0, clamp to [0, 1],
// sRGB transfer function on RGB, quantize to 8 bits. C++ reference: hmb::io::encodeDisplay.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "encode_display.h"
#include "../shared/layer_layout.h"

layout(local_size_x = HMB_ENCODE_DISPLAY_GROUP_X, local_size_y = HMB_ENCODE_DISPLAY_GROUP_Y) in;

layout(constant_id = HMB_SPEC_ENCODE_LAYER_SAMPLES) const bool kLayerSamples = false;
layout(std430, binding = HMB_ENCODE_DISPLAY_BINDING_LINEAR) readonly buffer Input { uvec4 pixels[]; };
layout(std430, binding = HMB_ENCODE_DISPLAY_BINDING_RGBA8) writeonly buffer DisplayImage { uint rgba8[]; };
layout(push_constant) uniform Params { EncodeDisplayParams params; };

float finiteOrZero(float x) { return (isnan(x) || isinf(x)) ? 0.0 : x; }

float linearToSrgb(float linear) {
  const float x = clamp(finiteOrZero(linear), 0.0, 1.0);
  return x <= 0.0031308 ? 12.92 * x : 1.055 * pow(x, 1.0 / 2.4) - 0.055;
}

uint quantize(float x) { return uint(clamp(x, 0.0, 1.0) * 255.0 + 0.5); }

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const uvec4 p = pixels[index];
  const vec4 c = kLayerSamples ? vec4(sampleColor(p), 1.0) : uintBitsToFloat(p);
  const uint r = quantize(linearToSrgb(c.r));
  const uint g = quantize(linearToSrgb(c.g));
  const uint b = quantize(linearToSrgb(c.b));
  const uint a = quantize(finiteOrZero(c.a));
  rgba8[index] = r | (g << 8) | (b << 16) | (a << 24);
}
