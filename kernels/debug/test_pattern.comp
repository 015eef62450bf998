#version 450
// Horizontal red ramp, vertical green ramp, a blue checker, and a white disc whose centre
// moves with time. C++ reference: testPatternPixel in tests/runtime.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "test_pattern.h"

layout(local_size_x = HMB_TEST_PATTERN_GROUP_X, local_size_y = HMB_TEST_PATTERN_GROUP_Y) in;

layout(std430, binding = HMB_TEST_PATTERN_BINDING_LINEAR) writeonly buffer LinearImage { vec4 linearRgba[]; };
layout(push_constant) uniform Params { TestPatternParams params; };

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const vec2 size = vec2(params.width, params.height);
  const vec2 centre = vec2(pixel) + 0.5;
  const vec2 uv = centre / size;
  const uvec2 cell = pixel / HMB_TEST_PATTERN_CHECKER;
  const float checker = ((cell.x + cell.y) & 1u) == 0u ? 0.25 : 0.75;
  vec4 colour = vec4(uv.x, uv.y, checker, 1.0);

  const vec2 discCentre = vec2(fract(params.time) * size.x, 0.5 * size.y);
  const float radius = 0.25 * min(size.x, size.y);
  const vec2 d = centre - discCentre;
  if (dot(d, d) <= radius * radius) colour = vec4(1.0);
  linearRgba[pixel.y * params.width + pixel.x] = colour;
}
