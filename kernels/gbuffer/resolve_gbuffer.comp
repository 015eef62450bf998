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
layout(std430, binding = HMB_RESOLVE_BINDING_CLIP_CURRENT) readonly buffer ClipCurrent { vec4 clipCurrent[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_CLIP_PREVIOUS) readonly buffer ClipPrevious { vec4 clipPrevious[]; };
layout(std430, binding = HMB_RESOLVE_BINDING_SHADING) readonly buffer Shading { GpuVertexShading shading[]; };
#define HMB_SCENE_BINDING HMB_RESOLVE_BINDING_SCENE
#include "../shared/scene_bindings.glsl"
#include "../shared/layer_bindings.glsl"
HMB_LAYER(gbuffer, HMB_RESOLVE_BINDING_GBUFFER, writeonly)
layout(push_constant) uniform Params { ResolveParams params; };

#include "../shared/shading.glsl"

// Barycentrics b (sum 1) of the point of triangle (c0, c1, c2) that projects to ndc:
// sum b_i (c_i.xy - ndc * c_i.w) = 0. They weight clip-space (hence world-space) attributes
// directly, i.e. they are already perspective-correct.
// Clip positions are passed as (x, y, w).
vec3 clipBarycentrics(vec3 c0, vec3 c1, vec3 c2, vec2 ndc) {
  const vec3 rowX = vec3(c0.x - ndc.x * c0.z, c1.x - ndc.x * c1.z, c2.x - ndc.x * c2.z);
  const vec3 rowY = vec3(c0.y - ndc.y * c0.z, c1.y - ndc.y * c1.z, c2.y - ndc.y * c2.z);
  const vec3 k = cross(rowX, rowY);
  const float sum = k.x + k.y + k.z;
  return sum != 0.0 ? k / sum : vec3(1.0 / 3.0);
}

// Clip position (x, y, w) to pixel coordinates.
vec2 clipToPixel(vec3 c) {
  return (c.xy / c.z * 0.5 + 0.5) * vec2(params.width, params.height);
}

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const uint triangleId = visibility[index].x;
  if (triangleId == HMB_VIS_EMPTY) {
    const vec3 background = camera.background.rgb;  // not inside the macro: `camera` is one
    WRITE_LAYER(gbuffer, index, background, vec3(0.0), 0u, params.backgroundDepth, vec2(0.0));
    return;
  }

  // Every word a kernel loads at a per-pixel address costs a gather on CPU devices, so this
  // reads only what it needs: clip x, y, w (w is camera-space depth), world normals and uvs.
  const GpuTriangle tri = triangles[triangleId];
  const vec2 centre = vec2(pixel) + 0.5;
  const vec2 ndc = centre / vec2(params.width, params.height) * 2.0 - 1.0;
  const vec3 c0 = clipCurrent[tri.v0].xyw, c1 = clipCurrent[tri.v1].xyw, c2 = clipCurrent[tri.v2].xyw;
  const vec3 b = clipBarycentrics(c0, c1, c2, ndc);

  vec3 n = b.x * shading[tri.v0].normal.xyz + b.y * shading[tri.v1].normal.xyz + b.z * shading[tri.v2].normal.xyz;
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  // A triangle seen from behind (only double-sided ones reach here) shades with its normal
  // turned to the viewer. The homogeneous determinant has the sign of the screen-space area
  // (positive: back face, y down) and stays right for vertices behind the camera.
  if (dot(c0, cross(c1, c2)) > 0.0) n = -n;
  const vec2 uv =
      kTexturePath ? b.x * shading[tri.v0].uv + b.y * shading[tri.v1].uv + b.z * shading[tri.v2].uv : vec2(0.0);

  const vec3 previousClip =
      b.x * clipPrevious[tri.v0].xyw + b.y * clipPrevious[tri.v1].xyw + b.z * clipPrevious[tri.v2].xyw;
  // A point behind the camera at the previous frame has no screen position: no velocity.
  const vec2 motion = previousClip.z > 0.0 ? centre - clipToPixel(previousClip) : vec2(0.0);

  // Clip w of a perspective projection is the camera-space depth, and linear in barycentrics.
  const float depth = dot(b, vec3(c0.z, c1.z, c2.z));
  const vec3 color = shadeSurface(sceneInstances[tri.instance].material, uv, n);
  const uint objectId = sceneInstances[tri.instance].objectId;
  WRITE_LAYER(gbuffer, index, color, n, objectId, depth, motion);  // non-finite motion packs as none
}
