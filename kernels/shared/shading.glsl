// The one shading function of every method (resolve, ray reveal, reference): base colour
// (factor x sRGB texture, bilinear, repeat), one directional light plus ambient, no shadows.
// Needs the Materials, Texels and Camera buffers declared by the including kernel. Reads
// fields one at a time (no struct copies): CPU devices gather every word a kernel loads.
#ifndef HMB_KERNELS_SHARED_SHADING_GLSL
#define HMB_KERNELS_SHARED_SHADING_GLSL

// False for scenes without textures: the texture path and the uv reads that feed it fold away.
layout(constant_id = HMB_SPEC_TEXTURE_PATH) const bool kTexturePath = true;

// Texel (x, y) of the texture at `offset` with rows of `width`, as linear RGBA (decoded from
// sRGB on upload: runtime/device_scene/gpu_scene.cpp).
vec4 texelLinear(uint offset, uint width, uint x, uint y) { return textureTexel(offset + y * width + x); }

vec4 baseColor(uint material, vec2 uv) {
  const uvec3 texture = kTexturePath ? materialTexture(material) : uvec3(HMB_NO_TEXTURE, 0u, 0u);
  const uint offset = texture.x;
  if (offset == HMB_NO_TEXTURE) return materialBaseColor(material);
  if (any(isnan(uv)) || any(isinf(uv))) uv = vec2(0.0);
  // Repeat wrap without integer division: fract puts uv in [0, 1], so the texel to the left
  // of a sample is in [-1, size - 1] and wraps with one comparison per axis.
  const ivec2 size = ivec2(texture.yz);
  const vec2 st = fract(uv) * vec2(size) - 0.5;
  const vec2 f = st - floor(st);
  const ivec2 i = clamp(ivec2(floor(st)), ivec2(-1), size - 1);
  const uvec2 lo = uvec2(mix(i, size - 1, lessThan(i, ivec2(0))));
  const uvec2 hi = uvec2(mix(i + 1, ivec2(0), greaterThanEqual(i + 1, size)));
  const uint width = uint(size.x);
  const vec4 c00 = texelLinear(offset, width, lo.x, lo.y);
  const vec4 c10 = texelLinear(offset, width, hi.x, lo.y);
  const vec4 c01 = texelLinear(offset, width, lo.x, hi.y);
  const vec4 c11 = texelLinear(offset, width, hi.x, hi.y);
  return materialBaseColor(material) * mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// n: unit world normal facing the viewer. Light from the frame's camera block: lightDirection
// is the direction light travels.
vec3 shadeSurface(uint material, vec2 uv, vec3 n) {
  const vec3 albedo = baseColor(material, uv).rgb;
  const float lambert = max(dot(n, -camera.lightDirection.xyz), 0.0);
  return albedo * (camera.ambient.rgb + camera.lightColor.rgb * lambert);
}

#endif
