// The clip volume of the rasterizer's setup: the near plane and a guard band of 4x the viewport
// (so snapped screen coordinates stay exact in float). Shared by setup_triangles (which tests
// against it) and clip_triangles (which clips against it).
#ifndef HMB_KERNELS_RASTER_CLIP_PLANES_GLSL
#define HMB_KERNELS_RASTER_CLIP_PLANES_GLSL

// Clip planes as dot(plane, clip) >= 0: near (z >= 0) and a guard band of 4x the viewport.
const float kGuardBand = 4.0;
const int kPlaneCount = 5;
const int kMaxPolygon = 3 + kPlaneCount;

float planeDistance(int plane, vec4 c) {
  switch (plane) {
    case 0: return c.z;
    case 1: return kGuardBand * c.w - c.x;
    case 2: return kGuardBand * c.w + c.x;
    case 3: return kGuardBand * c.w - c.y;
    default: return kGuardBand * c.w + c.y;
  }
}

// planeDistance(plane, c) >= 0 for every plane (the same comparisons, without the arrays).
bool insideClipVolume(vec4 c) {
  return c.z >= 0.0 && abs(c.x) <= kGuardBand * c.w && abs(c.y) <= kGuardBand * c.w;
}

#endif
