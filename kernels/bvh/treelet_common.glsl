// What the treelet builder's kernels share (treelet_build_layout.h): a primitive's centroid,
// a box's area, and a tile's group.
#ifndef HMB_KERNELS_BVH_TREELET_COMMON_GLSL
#define HMB_KERNELS_BVH_TREELET_COMMON_GLSL

#include "treelet_build_layout.h"

// A box's centre, or the origin where the box is empty or not finite (its primitive still gets
// a leaf; the binned builder's rule too).
vec3 treeletCentroid(BvhBox box) {
  const vec3 c = 0.5 * (box.min.xyz + box.max.xyz);
  return all(lessThanEqual(box.min.xyz, box.max.xyz)) && !any(isinf(c)) && !any(isnan(c)) ? c : vec3(0.0);
}

// Half a box's surface area (the SAH compares ratios), 0 for an empty box. Precise, so the host
// reference (bvh/treelet_reference.cpp) gets the same float.
float halfArea(vec3 lo, vec3 hi) {
  precise const vec3 e = max(hi - lo, vec3(0.0));
  precise const float area = e.x * e.y + e.y * e.z + e.z * e.x;
  return area;
}

#endif
