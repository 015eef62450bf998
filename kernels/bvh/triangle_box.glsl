// The box of a triangle as the builder bins it: a triangle with a non-finite vertex gets an
// empty box, so it can never be hit and never widens a node.
#ifndef HMB_KERNELS_BVH_TRIANGLE_BOX_GLSL
#define HMB_KERNELS_BVH_TRIANGLE_BOX_GLSL

#include "bvh_build_layout.h"

BvhBox triangleBox(vec3 a, vec3 b, vec3 c) {
  vec3 lo = min(a, min(b, c)), hi = max(a, max(b, c));
  const vec3 all3 = a + b + c;  // NaN or inf when any vertex is (or when they overflow)
  const bool finite = !any(isnan(all3)) && !any(isinf(all3)) && !any(isinf(a)) && !any(isinf(b)) && !any(isinf(c));
  if (!finite) {
    lo = vec3(uintBitsToFloat(0x7f800000u));
    hi = -lo;
  }
  BvhBox box;
  box.min = vec4(lo, 0.0);
  box.max = vec4(hi, 0.0);
  return box;
}

#endif
