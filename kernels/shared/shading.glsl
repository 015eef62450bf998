// The one shading function of every method (resolve, ray reveal, reference): base colour
// (factor x sRGB texture, bilinear, repeat), one directional light plus ambient, no shadows.
// Needs the Materials and Texels buffers declared by the including kernel.
#ifndef HMB_KERNELS_SHARED_SHADING_GLSL
#define HMB_KERNELS_SHARED_SHADING_GLSL

float srgbToLinear(float c) { return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4); }

vec4 texelLinear(GpuMaterial m, ivec2 t) {
  t = ivec2(uint(t.x) % m.textureWidth, uint(t.y) % m.textureHeight);
  const vec4 c = unpackUnorm4x8(texels[m.textureOffset + uint(t.y) * m.textureWidth + uint(t.x)]);
  return vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a);
}

vec4 baseColor(GpuMaterial m, vec2 uv) {
  if (m.textureOffset == HMB_NO_TEXTURE) return m.baseColor;
  // Repeat wrap; fract keeps huge uv values finite and in range.
  const vec2 st = fract(uv) * vec2(m.textureWidth, m.textureHeight) - 0.5;
  const ivec2 i = ivec2(floor(st));
  const vec2 f = st - vec2(i);
  const ivec2 wrap = ivec2(m.textureWidth, m.textureHeight);
  const vec4 c00 = texelLinear(m, (i + wrap) % wrap);
  const vec4 c10 = texelLinear(m, (i + ivec2(1, 0) + wrap) % wrap);
  const vec4 c01 = texelLinear(m, (i + ivec2(0, 1) + wrap) % wrap);
  const vec4 c11 = texelLinear(m, (i + ivec2(1, 1) + wrap) % wrap);
  return m.baseColor * mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// n: unit world normal facing the viewer; lightDirection: the direction light travels.
vec3 shadeSurface(GpuMaterial m, vec2 uv, vec3 n, GpuCamera camera) {
  const vec3 albedo = baseColor(m, uv).rgb;
  const float lambert = max(dot(n, -camera.lightDirection.xyz), 0.0);
  return albedo * (camera.ambient.rgb + camera.lightColor.rgb * lambert);
}

#endif
