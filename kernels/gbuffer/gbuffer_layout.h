// Layout of gbuffer/resolve_gbuffer.comp: visibility buffer -> G-buffer.
#ifndef HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H
#define HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H

#include "../shared/glsl_cpp.h"
#include "../shared/layer_layout.h"
#include "../shared/scene_layout.h"

#define HMB_RESOLVE_GROUP_X 8
#define HMB_RESOLVE_GROUP_Y 8

#define HMB_RESOLVE_BINDING_VISIBILITY 0
#define HMB_RESOLVE_BINDING_TRIANGLES 1
#define HMB_RESOLVE_BINDING_CLIP_CURRENT 2
#define HMB_RESOLVE_BINDING_CLIP_PREVIOUS 3
#define HMB_RESOLVE_BINDING_SHADING 4  // GpuVertexShading per instance vertex
// The scene (shared/scene_bindings.glsl), then the G-buffer written (shared/layer_bindings.glsl):
// colour (linear, opaque; the background colour where empty), normal and camera-space depth,
// velocity in pixels per frame (y down), object id (0 for the background).
#define HMB_RESOLVE_BINDING_SCENE 5
#define HMB_RESOLVE_BINDING_GBUFFER (HMB_RESOLVE_BINDING_SCENE + HMB_SCENE_BINDINGS)
// The G-buffer's velocities (vec2 per pixel, written: shared/layer_layout.h).
#define HMB_RESOLVE_BINDING_VELOCITIES (HMB_RESOLVE_BINDING_GBUFFER + HMB_LAYER_BINDINGS)
#define HMB_RESOLVE_BINDING_COUNT (HMB_RESOLVE_BINDING_VELOCITIES + 1)
// Read as uniform texel buffers: visibility, triangles, both clip positions, shading, and the
// scene's (scene_layout.h), counted in kernels/manifest.h.

HMB_GPU_BEGIN
struct ResolveParams {
  uint width;
  uint height;
  float backgroundDepth;  // camera-space depth written where no surface is hit (the far plane)
  uint pad0;
};
HMB_GPU_END
HMB_CHECK_SIZE(ResolveParams, 16)

// resolve_shutter_path: each pixel's screen path over the shutter, for the curved motion path.
// One uvec2 per pixel (the "paths" buffer): x, y = where the pixel's point is at t, minus where
// it is at mid-shutter (t - E/2) and at shutter open (t - E), in pixels (y down), as half
// floats (x low, y high), each kept within the largest half as velocities are. A pixel without
// a path (the background, a point behind the camera at either time) holds HMB_NO_SHUTTER_PATH
// in both words: half-float NaNs, which readers take as "follow the straight velocity".
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_VISIBILITY 0
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_TRIANGLES 1
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_CURRENT 2
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_MID 3
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_OPEN 4
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_PATHS 5
#define HMB_SHUTTER_PATH_RESOLVE_BINDING_COUNT 6
#define HMB_NO_SHUTTER_PATH 0xffffffffu

#endif
