#version 450
// Ray reveal (paper, section 3.2.2): for each pixel of the ray mask, the camera ray through
// the pixel centre at the frame time, continued behind the object the raster sees there (and
// started just short of the raster's surface).
//  - object-id stop (default): the traversal skips that object's instances whole, so one
//    trace finds the first surface of any other object (the paper's future work: our
//    traversal knows object ids).
//  - luminance stop (the paper's mode): step past hits, up to maxRecursion times, until a hit's
//    shaded luminance differs from the first hit's by more than the relative threshold; the
//    last hit is kept when none does.
// The revealed surface is shaded with the shading function every method shares (or a user's:
// trace/shade_hit.glsl) and written
// as a G-buffer entry: colour, normal and camera-space depth, screen velocity (the same
// surface point at t and t - 1/fps, as the resolve computes it) and object id. Nothing behind
// reads as the background colour at the far depth.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reveal_layout.h"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"
#define HMB_TRACE_SCENE_BINDING HMB_REVEAL_BINDING_TRACE_SCENE
#include "../trace/closest_hit.glsl"

layout(local_size_x = HMB_MASK_LIST_GROUP) in;

layout(std430, binding = HMB_REVEAL_BINDING_CAMERA_RAYS) readonly buffer CameraRays { PinholeCamera cameraRays; };
layout(std430, binding = HMB_REVEAL_BINDING_LIST) readonly buffer List { uint list[]; };
layout(std430, binding = HMB_REVEAL_BINDING_COUNTERS) buffer Counters { RayMaskCounters counters; };
#define HMB_SCENE_BINDING HMB_REVEAL_BINDING_SCENE
#include "../shared/scene_bindings.glsl"
#include "../shared/layer_bindings.glsl"
HMB_LAYER_TEXELS(raster, HMB_REVEAL_BINDING_RASTER)
HMB_LAYER(revealed, HMB_REVEAL_BINDING_REVEALED, writeonly)
layout(push_constant) uniform Params { RevealParams params; };
layout(constant_id = HMB_SPEC_REVEAL_STOP) const uint kStop = HMB_REVEAL_STOP_OBJECT_ID;

#include "../shared/shading.glsl"
#include "../trace/shade_hit.glsl"

float luminance(vec3 c) { return dot(c, vec3(0.2126, 0.7152, 0.0722)); }

// The smallest t past a hit at t: a few ulps on, so the same triangle is not met again.
float pastHit(float t) { return uintBitsToFloat(floatBitsToUint(max(t, 1e-30)) + 16u); }

// Nothing of another object lies nearer than the surface the raster sees at a pixel's centre
// (the same camera ray at the same time), so the ray starts a hundredth of that depth short of
// it and the traversal culls every node before it; the margin covers the rasterizer's and the
// traversal's different rounding. (A camera ray's t is camera-space depth: trace_layout.h.)
const float kStartShort = 0.99;

bool finite3(vec3 v) { return !any(isnan(v)) && !any(isinf(v)); }

void main() {
  const uint entry = linearInvocationIndex(HMB_MASK_LIST_GROUP);
  if (entry >= counters.maskCount) return;
  const uint index = list[entry];
  const uvec2 pixel = uvec2(index % params.width, index / params.width);
  const vec2 centre = vec2(pixel) + 0.5;

  // Where the raster's depth is not a positive number, from the near plane.
  const uvec4 rasterSurface = READ_LAYER_SURFACE(raster, index);  // its depth and object id
  const float rasterDepth = surfaceDepth(rasterSurface);
  const float start = rasterDepth > 0.0 ? min(rasterDepth * kStartShort, params.tMax) : params.tMin;

  TraceRay ray;
  ray.originTMin = vec4(cameraRays.eye.xyz, max(params.tMin, start));
  ray.directionTMax = vec4(pinholeRayDirection(cameraRays, centre, params.width, params.height), params.tMax);
  ray.time = 0u;
  ray.ignoreObjectId = HMB_IGNORE_NONE;
  ray.pad0 = 0u;
  ray.pad1 = 0u;
  const TraceSceneInfo scene = TraceSceneInfo(params.instanceCount, params.timeCount, HMB_TRACE_CULL_BACK_FACES);
  const vec3 direction = ray.directionTMax.xyz;

  BvhHit hit;
  uint traces = 1u;
  if (kStop == HMB_REVEAL_STOP_OBJECT_ID) {
    ray.ignoreObjectId = surfaceObjectId(rasterSurface);
    hit = closestHit(ray, scene);
  } else {
    hit = closestHit(ray, scene);
    if (hit.triangle != HMB_NO_HIT) {
      const vec3 eye = ray.originTMin.xyz;
      const float firstLuminance = luminance(shadeHit(hitRecord(hit, eye, direction, hit.instance * params.timeCount)));
      for (uint step = 0u; step < params.maxRecursion; ++step) {
        ray.originTMin.w = pastHit(hit.t);
        hit = closestHit(ray, scene);
        ++traces;
        if (hit.triangle == HMB_NO_HIT) break;
        const float difference = abs(luminance(shadeHit(hitRecord(hit, eye, direction, hit.instance * params.timeCount))) - firstLuminance);
        if (difference > params.luminanceThreshold * max(firstLuminance, 1e-3)) break;
      }
    }
  }

  // The object-id stop traces one ray per listed pixel: the first lane counts them all (an
  // atomic per ray on one counter, from every thread of a CPU device, cost a CPU device time:
  // bench/results/reveal-ray-count/).
  if (kStop != HMB_REVEAL_STOP_OBJECT_ID) atomicAdd(counters.rayCount, traces);
  else if (entry == 0u) atomicAdd(counters.rayCount, counters.maskCount);
  if (hit.triangle == HMB_NO_HIT) {
    const vec3 missed = shadeMiss(normalize(direction));
    const vec3 background = finite3(missed) ? missed : vec3(0.0);  // a user's shading too
    WRITE_LAYER(revealed, index, background, vec3(0.0), 0u, params.backgroundDepth, vec2(0.0));
    return;
  }
  // The hit point now and at the previous frame: carried into the instance's space with the
  // frame-time transform and out again with the previous one.
  const vec3 world = ray.originTMin.xyz + hit.t * direction;
  const vec4 objectPoint = objectFromWorldAt(hit.instance * params.timeCount) * vec4(world, 1.0);
  const vec4 previousClip = camera.viewProjPrevious * (instanceWorldPrevious(hit.instance) * objectPoint);
  vec2 motion = vec2(0.0);
  if (previousClip.w > 0.0) motion = centre - (previousClip.xy / previousClip.w * 0.5 + 0.5) * vec2(params.width, params.height);

  const HitRecord record = hitRecord(hit, ray.originTMin.xyz, direction, hit.instance * params.timeCount);
  const vec3 shaded = shadeHit(record);
  const vec3 color = finite3(shaded) ? shaded : vec3(0.0);  // a user's shading too
  WRITE_LAYER(revealed, index, color, record.normal, record.objectId, hit.t, motion);  // non-finite motion packs as none
}
