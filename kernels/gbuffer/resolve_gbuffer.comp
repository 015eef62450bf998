#version 450
// Visibility buffer -> G-buffer: for the triangle seen at each pixel centre, perspective-
// correct barycentrics from its clip-space vertices (valid for vertices behind the camera
// too, so near-clipped triangles need nothing special), then camera-space depth, world
// normal, object id, screen velocity (the same surface point at t and t - 1/fps) and the
// shaded colour.
#extension GL_GOOGLE_include_directive : require
#include "gbuffer_layout.h"
#include "../raster/raster_layout.h"
#include "../shared/scene_layout.h"

layout(local_size_x = HMB_RESOLVE_GROUP_X, local_size_y = HMB_RESOLVE_GROUP_Y) in;

layout(std430, binding = HMB_RESOLVE_BINDING_VISIBILITY) readonly buffer Visibility { uvec2 visibility[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_TRIANGLES) readonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_INSTANCE_VERTICES) readonly buffer InstanceVertices { GpuInstanceVertex instanceVertices[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_VERTICES) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_INSTANCES) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_MATERIALS) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_TEXELS) readonly buffer Texels { uint texels[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_CAMERA) readonly buffer Camera { GpuCamera camera; };
layout(std430, binding = HMB_RESOLVE_BINDING_CLIP_CURRENT) readonly buffer ClipCurrent { vec4 clipCurrent[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_CLIP_PREVIOUS) readonly buffer ClipPrevious { vec4 clipPrevious[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_COLOR) writeonly buffer Color { vec4 color[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_NORMAL_DEPTH) writeonly buffer NormalDepth { vec4 normalDepth[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_VELOCITY) writeonly buffer Velocity { vec2 velocity[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_OBJECT_ID) writeonly buffer ObjectId { uint objectId[]; };
layout(push_constant) uniform Params { ResolveParams params; };

#include "../shared/shading.glsl"

// Barycentrics b (sum 1) of the point of triangle (c0, c1, c2) that projects to ndc:
// sum b_i (c_i.xy - ndc * c_i.w) = 0. They weight clip-space (hence world-space) attributes
// directly, i.e. they are already perspective-correct.
vec3 clipBarycentrics(vec4 c0, vec4 c1, vec4 c2, vec2 ndc) {
  const vec3 rowX = vec3(c0.x - ndc.x * c0.w, c1.x - ndc.x * c1.w, c2.x - ndc.x * c2.w);
  const vec3 rowY = vec3(c0.y - ndc.y * c0.w, c1.y - ndc.y * c1.w, c2.y - ndc.y * c2.w);
  const vec3 k = cross(rowX, rowY);
  const float sum = k.x + k.y + k.z;
  return sum != 0.0 ? k / sum : vec3(1.0 / 3.0);
}

vec2 clipToPixel(vec4 c) {
  return (c.xy / c.w * 0.5 + 0.5) * vec2(params.width, params.height);
}

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const uint triangleId = visibility[index].x;
  if (triangleId == HMB_VIS_EMPTY) {
    color[index] = vec4(camera.background.rgb, 1.0);
    normalDepth[index] = vec4(0.0, 0.0, 0.0, params.backgroundDepth);
    velocity[index] = vec2(0.0);
    objectId[index] = 0u;
    return;
  }

  const GpuTriangle tri = triangles[triangleId];
  const GpuInstance instance = instances[tri.instance];
  const vec2 centre = vec2(pixel) + 0.5;
  const vec2 ndc = centre / vec2(params.width, params.height) * 2.0 - 1.0;
  const vec4 c0 = clipCurrent[tri.v0], c1 = clipCurrent[tri.v1], c2 = clipCurrent[tri.v2];
  const vec3 b = clipBarycentrics(c0, c1, c2, ndc);

  const GpuVertex v0 = vertices[instanceVertices[tri.v0].meshVertex];
  const GpuVertex v1 = vertices[instanceVertices[tri.v1].meshVertex];
  const GpuVertex v2 = vertices[instanceVertices[tri.v2].meshVertex];
  const vec3 objectNormal = b.x * v0.normal.xyz + b.y * v1.normal.xyz + b.z * v2.normal.xyz;
  vec3 n = mat3(instance.normalCurrent) * objectNormal;
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  const vec4 objectPosition = b.x * v0.position + b.y * v1.position + b.z * v2.position;
  const vec3 world = (instance.worldCurrent * objectPosition).xyz;
  // Double-sided surfaces seen from behind shade with the normal facing the viewer.
  if (dot(n, camera.positionCurrent.xyz - world) < 0.0) n = -n;
  const vec2 uv = b.x * v0.uv + b.y * v1.uv + b.z * v2.uv;

  const vec4 previousClip = b.x * clipPrevious[tri.v0] + b.y * clipPrevious[tri.v1] + b.z * clipPrevious[tri.v2];
  // A point behind the camera at the previous frame has no screen position: no velocity.
  const vec2 motion = previousClip.w > 0.0 ? centre - clipToPixel(previousClip) : vec2(0.0);

  const float depth = -(camera.viewCurrent * vec4(world, 1.0)).z;
  color[index] = vec4(shadeSurface(materials[instance.material], uv, n, camera), 1.0);
  normalDepth[index] = vec4(n, depth);
  velocity[index] = (any(isinf(motion)) || any(isnan(motion))) ? vec2(0.0) : motion;
  objectId[index] = instance.objectId;
}
