#version 450
// The G-buffer oracle's fragments: what resolve_gbuffer computes at a pixel centre, from the
// rasterizer's interpolated attributes, packed into the same two records
// (kernels/shared/layer_layout.h) and shaded by the same function (kernels/shared/shading.glsl).
#extension GL_GOOGLE_include_directive : require
#include "kernels/shared/scene_layout.h"
#include "kernels/shared/layer_layout.h"
#include "tests/oracle/shaders/gbuffer_oracle_layout.h"
#define HMB_SCENE_BINDING HMB_GBUFFER_ORACLE_BINDING_SCENE
#include "kernels/shared/scene_bindings.glsl"
#include "kernels/shared/shading.glsl"

layout(push_constant) uniform Params { GBufferOracleParams params; };

layout(location = 0) in vec3 inNormal;
layout(location = 1) in vec2 inUv;
layout(location = 2) in vec3 inPreviousClip;
layout(location = 3) in float inDepth;
layout(location = 4) flat in uint inInstance;

layout(location = 0) out uvec4 outSample;
layout(location = 1) out uvec4 outSurface;

void main() {
  vec3 n = dot(inNormal, inNormal) > 0.0 ? normalize(inNormal) : vec3(0.0, 0.0, 1.0);
  if (!gl_FrontFacing) n = -n;  // only double-sided triangles are drawn from behind
  const vec2 centre = gl_FragCoord.xy;
  const vec2 motion = inPreviousClip.z > 0.0
                          ? centre - (inPreviousClip.xy / inPreviousClip.z * 0.5 + 0.5) * vec2(params.width, params.height)
                          : vec2(0.0);
  const vec3 color = shadeSurface(instanceMaterial(inInstance), kTexturePath ? inUv : vec2(0.0), n);
  const uint objectId = instanceObjectId(inInstance);
  outSample = packLayerSample(color, inDepth, motion);
  outSurface = packLayerSurface(n, objectId, inDepth, motion);
}
