#version 450
// Visibility buffer -> G-buffer: for the triangle seen at each pixel centre, perspective-
// correct barycentrics from its clip-space vertices (valid for vertices behind the camera
// too, so near-clipped triangles need nothing special), then camera-space depth, world
// normal, object id, screen velocity (the same surface point at t and t - 1/fps) and the
// shaded colour, into the layer, and the velocity as floats beside it.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "gbuffer_layout.h"
#include "../raster/raster_layout.h"
#include "../shared/scene_layout.h"

layout(local_size_x = HMB_RESOLVE_GROUP_X, local_size_y = HMB_RESOLVE_GROUP_Y) in;

// What it reads comes through uniform texel buffers (shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_RESOLVE_BINDING_VISIBILITY) uniform utextureBuffer visibilityTexels;  // 2 entries a record
layout(binding = HMB_RESOLVE_BINDING_TRIANGLES) uniform utextureBuffer triangleTexels;        // GpuTriangle
layout(binding = HMB_RESOLVE_BINDING_CLIP_CURRENT) uniform utextureBuffer clipCurrentTexels;  // vec4
layout(binding = HMB_RESOLVE_BINDING_CLIP_PREVIOUS) uniform utextureBuffer clipPreviousTexels;
layout(binding = HMB_RESOLVE_BINDING_SHADING) uniform utextureBuffer shadingTexels;  // GpuVertexShading: 2 each
#define HMB_SCENE_BINDING HMB_RESOLVE_BINDING_SCENE
#include "../shared/scene_bindings.glsl"
#include "../shared/layer_bindings.glsl"
HMB_LAYER(gbuffer, HMB_RESOLVE_BINDING_GBUFFER, writeonly)
layout(std430, binding = HMB_RESOLVE_BINDING_VELOCITIES) writeonly buffer Velocities { vec2 velocities[]; };
layout(push_constant) uniform Params { ResolveParams params; };

vec3 clipCurrentXYW(uint v) { return floatRecordAt(clipCurrentTexels, v).xyw; }
vec3 clipPreviousXYW(uint v) { return floatRecordAt(clipPreviousTexels, v).xyw; }
vec3 shadingNormal(uint v) { return floatRecordAt(shadingTexels, 2u * v).xyz; }
vec2 shadingUv(uint v) { return floatRecordAt(shadingTexels, 2u * v + 1u).xy; }

#include "../shared/shading.glsl"

#include "clip_barycentrics.glsl"

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  // The entry's low word: the triangle (raster_layout.h).
  const uint triangleId = halfRecordAt(visibilityTexels, index).x;
  if (triangleId == HMB_VIS_EMPTY) {
    const vec3 background = camera.background.rgb;  // not inside the macro: `camera` is one
    WRITE_LAYER(gbuffer, index, background, vec3(0.0), 0u, params.backgroundDepth, vec2(0.0));
    velocities[index] = vec2(0.0);
    return;
  }

  // Every word a kernel loads at a per-pixel address costs a gather on CPU devices, so this
  // reads only what it needs: clip x, y, w (w is camera-space depth), world normals and uvs.
  const uvec4 triangle = recordAt(triangleTexels, triangleId);
  const GpuTriangle tri = GpuTriangle(triangle.x, triangle.y, triangle.z, triangle.w);
  const vec2 centre = vec2(pixel) + 0.5;
  const vec2 ndc = centre / vec2(params.width, params.height) * 2.0 - 1.0;
  const vec3 c0 = clipCurrentXYW(tri.v0), c1 = clipCurrentXYW(tri.v1), c2 = clipCurrentXYW(tri.v2);
  const vec3 b = clipBarycentrics(c0, c1, c2, ndc);

  vec3 n = b.x * shadingNormal(tri.v0) + b.y * shadingNormal(tri.v1) + b.z * shadingNormal(tri.v2);
  n = dot(n, n) > 0.0 ? normalize(n) : vec3(0.0, 0.0, 1.0);
  // A triangle seen from behind (only double-sided ones reach here) shades with its normal
  // turned to the viewer. The homogeneous determinant has the sign of the screen-space area
  // (positive: back face, y down) and stays right for vertices behind the camera.
  if (dot(c0, cross(c1, c2)) > 0.0) n = -n;
  const vec2 uv =
      kTexturePath ? b.x * shadingUv(tri.v0) + b.y * shadingUv(tri.v1) + b.z * shadingUv(tri.v2) : vec2(0.0);

  const vec3 previousClip =
      b.x * clipPreviousXYW(tri.v0) + b.y * clipPreviousXYW(tri.v1) + b.z * clipPreviousXYW(tri.v2);
  // A point behind the camera at the previous frame has no screen position: no velocity.
  const vec2 motion = previousClip.z > 0.0 ? centre - clipToPixel(previousClip, params.width, params.height) : vec2(0.0);

  // Clip w of a perspective projection is the camera-space depth, and linear in barycentrics.
  const float depth = dot(b, vec3(c0.z, c1.z, c2.z));
  const vec3 color = shadeSurface(instanceMaterial(tri.instance), uv, n);
  const uint objectId = instanceObjectId(tri.instance);
  WRITE_LAYER(gbuffer, index, color, n, objectId, depth, motion);  // non-finite motion packs as none
  velocities[index] = layerVelocityEntry(motion);
}
