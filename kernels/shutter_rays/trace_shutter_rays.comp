#version 450
// Per pixel of list_shutter_rays' list: camera rays through the pixel centre at `rays` of the
// frame's shutter strata (every strata / rays-th from the pixel's first: stratified), each
// traced against the scene at its stratum's time (instances carried by their transforms at that
// time, the camera at that time) and shaded by the shading function every method shares, as
// the reference's samples are. Their mean replaces the colour the composite wrote there.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "shutter_rays_layout.h"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"
#define HMB_TRACE_SCENE_BINDING HMB_SHUTTER_TRACE_BINDING_TRACE_SCENE
#include "../trace/closest_hit.glsl"

layout(local_size_x = HMB_MASK_LIST_GROUP) in;

layout(std430, binding = HMB_SHUTTER_TRACE_BINDING_CAMERAS) readonly buffer Cameras { PinholeCamera cameras[]; };
layout(std430, binding = HMB_SHUTTER_TRACE_BINDING_LIST) readonly buffer List { uint list[]; };
layout(std430, binding = HMB_SHUTTER_TRACE_BINDING_COUNTERS) buffer Counters { ShutterRayCounters counters; };
layout(std430, binding = HMB_SHUTTER_TRACE_BINDING_OUTPUT) buffer Output { vec4 outputColor[]; };
#define HMB_SCENE_BINDING HMB_SHUTTER_TRACE_BINDING_SCENE
#include "../shared/scene_bindings.glsl"
layout(push_constant) uniform Params { ShutterRayTraceParams params; };

#include "../shared/shading.glsl"
#include "../trace/shade_hit.glsl"
#include "../trace/camera_ray_color.glsl"

void main() {
  const uint entry = linearInvocationIndex(HMB_MASK_LIST_GROUP);
  if (entry >= counters.count) return;
  const uint listed = list[entry];
  const uint index = shutterRayEntryPixel(listed);
  const uint rays = shutterRayEntryRays(listed);
  const uvec2 pixel = uvec2(index % params.width, index / params.width);
  const uint step = params.strata / rays;
  const TraceSceneInfo scene = TraceSceneInfo(params.instanceCount, params.timeCount, HMB_TRACE_CULL_BACK_FACES);

  vec3 sum = vec3(0.0);
  for (uint k = 0u, stratum = shutterRayFirstStratum(index, rays, params.strata); k < rays; ++k, stratum += step) {
    const uint time = 1u + stratum;
    sum += cameraRayColor(cameras[time], vec2(pixel) + 0.5, params.width, params.height, params.tMin, params.tMax,
                          time, scene);
  }
  atomicAdd(counters.rayCount, rays);
  outputColor[index] = vec4(sum / float(rays), 1.0);
}
