// What the G-buffer's resolves share: the perspective-correct barycentrics of the point of a
// triangle seen at a pixel, from its clip-space vertices, and clip space to pixels.
#ifndef HMB_KERNELS_GBUFFER_CLIP_BARYCENTRICS_GLSL
#define HMB_KERNELS_GBUFFER_CLIP_BARYCENTRICS_GLSL

// Barycentrics b (sum 1) of the point of triangle (c0, c1, c2) that projects to ndc:
// sum b_i (c_i.xy - ndc * c_i.w) = 0. They weight clip-space (hence world-space) attributes
// directly, i.e. they are already perspective-correct; valid for vertices behind the camera
// too. Clip positions are passed as (x, y, w).
vec3 clipBarycentrics(vec3 c0, vec3 c1, vec3 c2, vec2 ndc) {
  const vec3 rowX = vec3(c0.x - ndc.x * c0.z, c1.x - ndc.x * c1.z, c2.x - ndc.x * c2.z);
  const vec3 rowY = vec3(c0.y - ndc.y * c0.z, c1.y - ndc.y * c1.z, c2.y - ndc.y * c2.z);
  const vec3 k = cross(rowX, rowY);
  const float sum = k.x + k.y + k.z;
  return sum != 0.0 ? k / sum : vec3(1.0 / 3.0);
}

// Clip position (x, y, w) to pixel coordinates of a width x height image.
vec2 clipToPixel(vec3 c, uint width, uint height) { return (c.xy / c.z * 0.5 + 0.5) * vec2(width, height); }

#endif
