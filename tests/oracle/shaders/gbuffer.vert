#version 450
// The G-buffer oracle's vertices, pulled by index: vertex 3t + k is corner k of scene triangle t,
// at the clip-space position the transform kernel wrote, with its normal, uv and previous clip
// position as attributes the rasterizer interpolates perspective-correctly (as the resolve's
// barycentrics do).
#extension GL_GOOGLE_include_directive : require
#include "kernels/shared/scene_layout.h"
#include "tests/oracle/shaders/gbuffer_oracle_layout.h"

layout(std430, binding = HMB_GBUFFER_ORACLE_BINDING_TRIANGLES) readonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = HMB_GBUFFER_ORACLE_BINDING_CLIP_CURRENT) readonly buffer ClipCurrent { vec4 clipCurrent[]; };
layout(std430, binding = HMB_GBUFFER_ORACLE_BINDING_CLIP_PREVIOUS) readonly buffer ClipPrevious { vec4 clipPrevious[]; };
layout(std430, binding = HMB_GBUFFER_ORACLE_BINDING_SHADING) readonly buffer Shading { GpuVertexShading shading[]; };

layout(location = 0) out vec3 outNormal;
layout(location = 1) out vec2 outUv;
layout(location = 2) out vec3 outPreviousClip;  // x, y, w
layout(location = 3) out float outDepth;        // clip w: camera-space depth
layout(location = 4) flat out uint outInstance;

void main() {
  const uint t = uint(gl_VertexIndex) / 3u, corner = uint(gl_VertexIndex) % 3u;
  const GpuTriangle tri = triangles[t];
  const uint v = corner == 0u ? tri.v0 : (corner == 1u ? tri.v1 : tri.v2);
  const vec4 clip = clipCurrent[v];
  gl_Position = clip;
  outNormal = shading[v].normal.xyz;
  outUv = shading[v].uv;
  outPreviousClip = clipPrevious[v].xyw;
  outDepth = clip.w;
  outInstance = tri.instance;  // the same on all three corners: no provoking-vertex convention
}
