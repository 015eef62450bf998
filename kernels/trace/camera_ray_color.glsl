// The colour one camera ray sees at one shutter time, for the kernels that sample the shutter
// with rays (the reference's samples, the hybrid's shutter rays): the ray through image position
// `position` (pixels) of `cam`, traced through the trace scene at its time index `time`
// (instances carried by their transforms then, back faces culled as the rasterizer culls them),
// its first hit shaded (shade_hit.glsl: the shared shading or a user's), shadeMiss where
// nothing is hit (the scene's background or a user's), black where either gives no finite
// colour. Include after closest_hit.glsl, shared/shading.glsl, shade_hit.glsl and the scene's
// bindings.
#ifndef HMB_KERNELS_TRACE_CAMERA_RAY_COLOR_GLSL
#define HMB_KERNELS_TRACE_CAMERA_RAY_COLOR_GLSL

vec3 cameraRayColor(PinholeCamera cam, vec2 position, uint width, uint height, float tMin, float tMax, uint time,
                    TraceSceneInfo scene) {
  TraceRay ray;
  ray.originTMin = vec4(cam.eye.xyz, tMin);
  ray.directionTMax = vec4(pinholeRayDirection(cam, position, width, height), tMax);
  ray.time = time;
  ray.ignoreObjectId = HMB_IGNORE_NONE;
  ray.pad0 = 0u;
  ray.pad1 = 0u;
  const BvhHit hit = closestHit(ray, scene);
  const vec3 color = hit.triangle == HMB_NO_HIT
                         ? shadeMiss(normalize(ray.directionTMax.xyz))
                         : shadeHit(hitRecord(hit, ray.originTMin.xyz, ray.directionTMax.xyz,
                                              hit.instance * scene.timeCount + time));
  return any(isnan(color)) || any(isinf(color)) ? vec3(0.0) : color;
}

#endif
