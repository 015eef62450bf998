#version 450
#extension GL_GOOGLE_include_directive : require
// The consumer's own shader uses the same shading functions (as an engine's fragment shader
// would), compiled with the installed include alone: the include is whole without the library.
#include "shade_hit.glsl"
#include "shade_miss.glsl"

layout(location = 0) in vec3 normal;
layout(location = 0) out vec4 color;

void main() {
  HitRecord hit;
  hit.objectId = 1u;
  hit.instance = 0u;
  hit.barycentrics = vec2(0.0);
  hit.position = vec3(0.0);
  hit.normal = normalize(normal);
  hit.uv = vec2(0.0);
  hit.material = 0u;
  color = vec4(normal.z < 0.0 ? shadeMiss(normal) : shadeHit(hit), 1.0);
}
