#version 450
// The reference's mean: each pixel's sum of samples over their count.
#extension GL_GOOGLE_include_directive : require
#include "reference_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_REFERENCE_AVERAGE_GROUP) in;

layout(std430, binding = HMB_AVERAGE_BINDING_SUM) readonly buffer Sum { vec4 sum[]; };
layout(std430, binding = HMB_AVERAGE_BINDING_COLOR) writeonly buffer Color { vec4 color[]; };
layout(push_constant) uniform Params { AverageParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_REFERENCE_AVERAGE_GROUP);
  if (i >= params.pixelCount) return;
  color[i] = vec4(sum[i].rgb / float(max(params.sampleCount, 1u)), 1.0);
}
