// A mask pixel's own path over the shutter, X + u v + u^2 q (mblur_common.glsl's inversePath),
// found alike by range_check, which walks it, and mask_coverage, which samples it, so that the
// coverage test takes its samples along the path the range check walked. The including kernel
// defines surfaceAt and shutterPathAt (the G-buffer's records) and binds `params`
// (RayMaskParams); include after mblur_common.glsl.
#ifndef HMB_KERNELS_HYBRID_OWN_CURVED_PATH_GLSL
#define HMB_KERNELS_HYBRID_OWN_CURVED_PATH_GLSL

// False, with v left as it is and q 0, for a pixel without a path. Else v and q are the path's
// terms: its record's, with the change of velocity towards X + a (a, its linear term) where
// that point lies on the pixel's surface (depth within SOFT_Z_EXTENT of ownDepth).
bool ownCurvedPath(uvec2 pixel, uint index, uvec4 ownSurface, float ownDepth, inout vec2 v, out vec2 q) {
  q = vec2(0.0);
  vec2 a, c;
  if (!shutterPathTerms(shutterPathAt(index), a, c)) return false;
  const ivec2 ahead = nearestPixel(vec2(pixel) + 0.5 + a, params.blur.width, params.blur.height);
  const uint aheadIndex = uint(ahead.y) * params.blur.width + uint(ahead.x);
  const uvec4 aheadSurface = surfaceAt(aheadIndex);
  const bool sameSurface = abs(sanitizeDepth(surfaceDepth(aheadSurface)) - ownDepth) < params.blur.softZExtent;
  const vec2 change = sameSurface ? (surfaceVelocity(aheadSurface) - surfaceVelocity(ownSurface)) *
                                        params.blur.velocityScale
                                  : vec2(0.0);
  inversePath(a, c, change, params.blur.maxSpeed, v, q);
  return true;
}

#endif
