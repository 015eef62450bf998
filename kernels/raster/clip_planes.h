// The clip volume of the rasterizer's setup: the near plane and a guard band four times the
// viewport (so snapped screen coordinates stay exact in float). Shared by setup_triangles
// (which tests against it), clip_triangles (which clips against it) and the C++ reference.
#ifndef HMB_KERNELS_RASTER_CLIP_PLANES_H
#define HMB_KERNELS_RASTER_CLIP_PLANES_H

#include "../shared/glsl_cpp.h"

HMB_GPU_BEGIN

// Clip planes as dot(plane, clip) >= 0: near (z <= w: depth is reversed, 1 at the near plane)
// and a guard band four times the viewport. The far plane (z >= 0) is left to each pixel's depth.
const float kGuardBand = 4.0f;
const int kPlaneCount = 5;
const int kMaxPolygon = 3 + kPlaneCount;

HMB_SHARED float planeDistance(int plane, vec4 c) {
  switch (plane) {
    case 0: return c.w - c.z;
    case 1: return kGuardBand * c.w - c.x;
    case 2: return kGuardBand * c.w + c.x;
    case 3: return kGuardBand * c.w - c.y;
    default: return kGuardBand * c.w + c.y;
  }
}

// planeDistance(plane, c) >= 0 for every plane (the same comparisons, without the arrays).
HMB_SHARED bool insideClipVolume(vec4 c) {
  return c.z <= c.w && abs(c.x) <= kGuardBand * c.w && abs(c.y) <= kGuardBand * c.w;
}

HMB_GPU_END

#endif
