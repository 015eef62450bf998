#version 450
// The reference's mean: each pixel's sum of samples (the sum tree's total, in one slot) over
// their count (in w: pixels that nothing moving crosses were sampled once).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reference_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_REFERENCE_AVERAGE_GROUP) in;

layout(std430, binding = HMB_AVERAGE_BINDING_SUMS) readonly buffer Sums { vec4 sums[]; };
layout(std430, binding = HMB_AVERAGE_BINDING_COLOR) writeonly buffer Color { vec4 color[]; };
layout(push_constant) uniform Params { AverageParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_REFERENCE_AVERAGE_GROUP);
  if (i >= params.pixelCount) return;
  const vec4 s = sums[params.sumSlot * params.pixelCount + i];
  color[params.firstPixel + i] = vec4(s.w > 0.0 ? s.rgb / s.w : vec3(0.0), 1.0);
}
