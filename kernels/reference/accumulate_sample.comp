#version 450
// One time sample of every pixel of the reference: the camera ray at the sample's shutter
// time, traced against the scene at that time (instances carried by their transforms at that
// time, so any motion is exact), shaded by the shading function every method shares, and
// added into the pixel's sum tree (runtime/passes/reference_sum_tree.h): the held nodes it
// completes are added to it, nearest first, each as the left operand, and the new node is
// written to its slot. One
// dispatch per sample: each invocation owns its pixel's sums.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reference_layout.h"
#include "../shared/indexing.glsl"
#include "../shared/scene_layout.h"
#define HMB_TRACE_SCENE_BINDING HMB_REFERENCE_BINDING_TRACE_SCENE
#include "../trace/closest_hit.glsl"

layout(local_size_x = HMB_REFERENCE_GROUP_X, local_size_y = HMB_REFERENCE_GROUP_Y) in;

layout(std430, binding = HMB_REFERENCE_BINDING_CAMERAS) readonly buffer Cameras { PinholeCamera cameras[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_SUMS) buffer Sums { vec4 sums[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_PIXELS) readonly buffer Pixels { uint pixelList[]; };
#define HMB_SCENE_BINDING HMB_REFERENCE_BINDING_SCENE
#include "../shared/scene_bindings.glsl"
layout(push_constant) uniform Params { ReferenceSampleParams params; };

#include "../shared/shading.glsl"
#include "../trace/shade_hit.glsl"
#include "../trace/camera_ray_color.glsl"

// PCG hash (O'Neill 2014 output function): decorrelates pixels and samples for the jitter.
uint pcgHash(uint x) {
  const uint state = x * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float unitFloat(uint bits) { return float(bits >> 8) * (1.0 / 16777216.0); }

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if ((params.flags & HMB_REFERENCE_PIXEL_LIST) != 0u) {
    // List mode: a 1D run of 8x8 groups over the list's entries.
    const uint entry = linearInvocationIndex(HMB_REFERENCE_GROUP_X * HMB_REFERENCE_GROUP_Y);
    if (entry >= params.listLength) return;
    const uint listed = pixelList[entry];
    pixel = uvec2(listed % params.width, listed / params.width);
  }
  if ((params.flags & HMB_REFERENCE_PIXEL_LIST) == 0u) pixel.y += params.bandFirstRow;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  if (pixel.y < params.bandFirstRow || pixel.y - params.bandFirstRow >= params.bandRows) return;
  const uint index = pixel.y * params.width + pixel.x;

  vec2 offset = vec2(0.5);
  if ((params.flags & HMB_REFERENCE_PIXEL_JITTER) != 0u) {
    const uint h = pcgHash(index ^ pcgHash(params.sampleIndex ^ pcgHash(params.seed)));
    offset = vec2(unitFloat(h), unitFloat(pcgHash(h)));
  }
  const TraceSceneInfo scene = TraceSceneInfo(params.instanceCount, params.timeCount, HMB_TRACE_CULL_BACK_FACES);
  const vec3 color = cameraRayColor(cameras[params.time], vec2(pixel) + offset, params.width, params.height,
                                    params.tMin, params.tMax, params.time, scene);
  const uint bandPixels = params.bandRows * params.width;
  const uint inBand = (pixel.y - params.bandFirstRow) * params.width + pixel.x;
  vec4 node = vec4(color, 1.0);
  for (uint i = 0u; i < params.foldCount; ++i) node = sums[params.foldSlots[i / 4u][i % 4u] * bandPixels + inBand] + node;
  sums[params.targetSlot * bandPixels + inBand] = node;
}
