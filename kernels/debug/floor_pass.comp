#version 450
// The benchmarks' floor: each pixel reads one 16-byte word and writes it back changed, in the
// 8x8 groups and row-major addressing the per-pixel passes use. Every per-pixel pass is reported
// as a multiple of this pass's time in the same run (bench/floor_pass.h).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "floor_pass.h"

layout(local_size_x = HMB_FLOOR_GROUP_X, local_size_y = HMB_FLOOR_GROUP_Y) in;

layout(std430, binding = HMB_FLOOR_BINDING_INPUT) readonly buffer Input { uvec4 pixelsIn[]; };
layout(std430, binding = HMB_FLOOR_BINDING_OUTPUT) writeonly buffer Output { uvec4 pixelsOut[]; };
layout(push_constant) uniform Params { FloorParams params; };

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  pixelsOut[index] = pixelsIn[index] + uvec4(1u);
}
