// Layout of gbuffer/resolve_gbuffer.comp: visibility buffer -> G-buffer.
#ifndef HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H
#define HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_RESOLVE_GROUP_X 8
#define HMB_RESOLVE_GROUP_Y 8

#define HMB_RESOLVE_BINDING_VISIBILITY 0
#define HMB_RESOLVE_BINDING_TRIANGLES 1
#define HMB_RESOLVE_BINDING_SCENE 2          // SceneTable (shared/scene_layout.h)
#define HMB_RESOLVE_BINDING_CLIP_CURRENT 3
#define HMB_RESOLVE_BINDING_CLIP_PREVIOUS 4
#define HMB_RESOLVE_BINDING_SHADING 5        // GpuVertexShading per instance vertex
#define HMB_RESOLVE_BINDING_GBUFFER 6        // LayerTable (shared/layer_layout.h): the G-buffer written
#define HMB_RESOLVE_BINDING_COUNT 7

HMB_GPU_BEGIN
struct ResolveParams {
  uint width;
  uint height;
  float backgroundDepth;  // camera-space depth written where no surface is hit (the far plane)
  uint pad0;
};
HMB_GPU_END
HMB_CHECK_SIZE(ResolveParams, 16)

#endif
