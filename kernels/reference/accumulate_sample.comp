#version 450
// One time sample of every pixel of the reference: the camera ray at the sample's shutter
// time, traced against the scene at that time (instances carried by their transforms at that
// time, so any motion is exact), shaded by the shading function every method shares, and
// added to the pixel's sum. One dispatch per sample: each invocation owns its pixel's sum.
#extension GL_GOOGLE_include_directive : require
#include "reference_layout.h"
#include "../shared/scene_layout.h"
#include "../trace/closest_hit.glsl"

layout(local_size_x = HMB_REFERENCE_GROUP_X, local_size_y = HMB_REFERENCE_GROUP_Y) in;

layout(std430, binding = HMB_REFERENCE_BINDING_CAMERAS) readonly buffer Cameras { ReferenceCamera cameras[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_SUM) buffer Sum { vec4 sum[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_VERTICES) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_INSTANCES) readonly buffer SceneInstances { GpuInstance sceneInstances[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_MATERIALS) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_TEXELS) readonly buffer Texels { uint texels[]; };
layout(std430, binding = HMB_REFERENCE_BINDING_CAMERA) readonly buffer Camera { GpuCamera camera; };
layout(std430, binding = HMB_REFERENCE_BINDING_PIXELS) readonly buffer Pixels { uint pixelList[]; };
layout(push_constant) uniform Params { ReferenceSampleParams params; };

#include "../shared/shading.glsl"

// PCG hash (O'Neill 2014 output function): decorrelates pixels and samples for the jitter.
uint pcgHash(uint x) {
  const uint state = x * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

float unitFloat(uint bits) { return float(bits >> 8) * (1.0 / 16777216.0); }

// Colour of the surface hit by the ray: normal and uv interpolated from the mesh's vertices,
// the normal carried to world space with the instance's transform at the ray's time and
// turned to the viewer when a (double-sided) back face is seen, as the G-buffer resolve does.
vec3 shadeHit(BvhHit hit, vec3 direction) {
  const uvec4 tri = traceTriangles[hit.triangle];
  const vec3 b = vec3(1.0 - hit.u - hit.v, hit.u, hit.v);
  const vec3 objectNormal = b.x * vertices[tri.x].normal.xyz + b.y * vertices[tri.y].normal.xyz +
                            b.z * vertices[tri.z].normal.xyz;
  const vec2 uv = b.x * vertices[tri.x].uv + b.y * vertices[tri.y].uv + b.z * vertices[tri.z].uv;
  const mat3 objectFromWorld = mat3(transforms[hit.instance * params.timeCount + params.time].objectFromWorld);
  const mat3 normalToWorld = transpose(objectFromWorld);
  vec3 n = normalToWorld * objectNormal;
  n = dot(n, n) > 0.0 && !any(isinf(n)) ? normalize(n) : vec3(0.0, 0.0, 1.0);
  // cross(M a, M b) = det(M) M^-T cross(a, b): the world counter-clockwise normal.
  const vec3 p0 = positions[tri.x].xyz, p1 = positions[tri.y].xyz, p2 = positions[tri.z].xyz;
  const float handedness = determinant(objectFromWorld) < 0.0 ? -1.0 : 1.0;
  const vec3 geometric = handedness * (normalToWorld * cross(p1 - p0, p2 - p0));
  if (dot(geometric, direction) > 0.0) n = -n;
  return shadeSurface(sceneInstances[hit.instance].material, uv, n);
}

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if ((params.flags & HMB_REFERENCE_PIXEL_LIST) != 0u) {
    // List mode: a 1D run of 8x8 groups over the list's entries.
    const uint entry = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) *
                           (HMB_REFERENCE_GROUP_X * HMB_REFERENCE_GROUP_Y) +
                       gl_LocalInvocationID.y * HMB_REFERENCE_GROUP_X + gl_LocalInvocationID.x;
    if (entry >= params.listLength) return;
    const uint listed = pixelList[entry];
    pixel = uvec2(listed % params.width, listed / params.width);
  }
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;

  vec2 offset = vec2(0.5);
  if ((params.flags & HMB_REFERENCE_PIXEL_JITTER) != 0u) {
    const uint h = pcgHash(index ^ pcgHash(params.sampleIndex ^ pcgHash(params.seed)));
    offset = vec2(unitFloat(h), unitFloat(pcgHash(h)));
  }
  const vec2 ndc = (vec2(pixel) + offset) / vec2(params.width, params.height) * 2.0 - 1.0;
  const ReferenceCamera cam = cameras[params.time];
  TraceRay ray;
  ray.originTMin = vec4(cam.eye.xyz, params.tMin);
  ray.directionTMax = vec4(cam.forward.xyz + ndc.x * cam.right.xyz + ndc.y * cam.down.xyz, params.tMax);
  ray.time = params.time;
  ray.ignoreObjectId = HMB_IGNORE_NONE;
  ray.pad0 = 0u;
  ray.pad1 = 0u;

  const BvhHit hit = closestHit(ray, TraceSceneInfo(params.instanceCount, params.timeCount, HMB_TRACE_CULL_BACK_FACES));
  vec3 color = hit.triangle == HMB_NO_HIT ? camera.background.rgb : shadeHit(hit, ray.directionTMax.xyz);
  if (any(isnan(color)) || any(isinf(color))) color = vec3(0.0);
  sum[index] += vec4(color, 1.0);
}
