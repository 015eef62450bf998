// Layouts of the rasterizer's kernels: transform -> setup (cull, near clip, snap, bin) ->
// rasterize tiles (visibility buffer) -> gbuffer/resolve.
#ifndef HMB_KERNELS_RASTER_RASTER_LAYOUT_H
#define HMB_KERNELS_RASTER_RASTER_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_RASTER_GROUP 64
// Screen tiles of the binner, in pixels: one (triangle, tile) pair is one invocation's work.
#define HMB_RASTER_TILE 8
// Sub-pixel precision: vertices snap to 1/256 pixel, so shared edges evaluate identically.
#define HMB_RASTER_SUBPIXEL 256.0

// A visibility-buffer entry is uint64 (depth bits << 32 | triangle id), read as uvec2
// (x = triangle id, y = depth bits). Cleared to all ones: no triangle, farthest depth.
#define HMB_VIS_EMPTY 0xffffffffu

// transform_vertices
#define HMB_TRANSFORM_BINDING_VERTICES 0
#define HMB_TRANSFORM_BINDING_INSTANCE_VERTICES 1
#define HMB_TRANSFORM_BINDING_INSTANCES 2
#define HMB_TRANSFORM_BINDING_CAMERA 3
#define HMB_TRANSFORM_BINDING_CLIP_CURRENT 4
#define HMB_TRANSFORM_BINDING_CLIP_PREVIOUS 5
#define HMB_TRANSFORM_BINDING_COUNT 6

// setup_triangles
#define HMB_SETUP_BINDING_TRIANGLES 0
#define HMB_SETUP_BINDING_INSTANCES 1
#define HMB_SETUP_BINDING_CLIP_CURRENT 2
#define HMB_SETUP_BINDING_SETUP 3      // SetupTriangle[]
#define HMB_SETUP_BINDING_PAIRS 4      // uvec2 (setup index, tile index)[]
#define HMB_SETUP_BINDING_COUNTERS 5   // RasterCounters
#define HMB_SETUP_BINDING_COUNT 6

// rasterize_tiles
#define HMB_RASTERIZE_BINDING_SETUP 0
#define HMB_RASTERIZE_BINDING_PAIRS 1
#define HMB_RASTERIZE_BINDING_COUNTERS 2
#define HMB_RASTERIZE_BINDING_VISIBILITY 3
#define HMB_RASTERIZE_BINDING_COUNT 4

HMB_GPU_BEGIN

struct RasterParams {
  uint width;
  uint height;
  uint triangleCount;      // setup: triangles in; rasterize: unused
  uint setupCapacity;      // SetupTriangle slots
  uint pairCapacity;       // (triangle, tile) pair slots
  uint tilesX;
  uint pass;               // rasterize_depth32: 0 writes depth, 1 writes ids where depth matches
  uint pad0;
};

// A triangle ready to rasterize: snapped screen positions (pixels, y down) ordered so that
// the inside has positive edge functions, depth z/w per vertex, and its pixel bounds.
struct SetupTriangle {
  vec2 p0;
  vec2 p1;
  vec2 p2;
  uint triangle;      // id of the scene triangle it came from (near clipping may split one)
  uint bounds;        // unused padding slot kept for alignment
  vec4 depth;         // xyz: z/w at p0, p1, p2
  uvec4 pixelBounds;  // inclusive pixel rectangle: x0, y0, x1, y1
};

// Atomic counters of one frame, with an indirect dispatch for the rasterize pass.
struct RasterCounters {
  uint setupCount;
  uint pairCount;
  uint dispatchX;  // indirect dispatch of rasterize_tiles: groups along x
  uint dispatchY;
  uint dispatchZ;
  uint overflow;   // non-zero when a capacity was exceeded (the host grows and re-renders)
  uint pad0;
  uint pad1;
};

HMB_GPU_END

HMB_CHECK_SIZE(RasterParams, 32)
HMB_CHECK_SIZE(SetupTriangle, 64)
HMB_CHECK_SIZE(RasterCounters, 32)

#endif
