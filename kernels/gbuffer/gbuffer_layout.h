// Layout of gbuffer/resolve_gbuffer.comp: visibility buffer -> G-buffer.
#ifndef HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H
#define HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_RESOLVE_GROUP_X 8
#define HMB_RESOLVE_GROUP_Y 8

#define HMB_RESOLVE_BINDING_VISIBILITY 0
#define HMB_RESOLVE_BINDING_TRIANGLES 1
#define HMB_RESOLVE_BINDING_INSTANCES 2
#define HMB_RESOLVE_BINDING_MATERIALS 3
#define HMB_RESOLVE_BINDING_TEXELS 4
#define HMB_RESOLVE_BINDING_CAMERA 5
#define HMB_RESOLVE_BINDING_CLIP_CURRENT 6
#define HMB_RESOLVE_BINDING_CLIP_PREVIOUS 7
#define HMB_RESOLVE_BINDING_SHADING 8        // GpuVertexShading per instance vertex
#define HMB_RESOLVE_BINDING_COLOR 9          // vec4: linear shaded colour, opaque (background colour where empty)
#define HMB_RESOLVE_BINDING_NORMAL_DEPTH 10  // vec4: xyz world normal, w camera-space depth
#define HMB_RESOLVE_BINDING_VELOCITY 11      // vec2: screen velocity, pixels per frame (y down)
#define HMB_RESOLVE_BINDING_OBJECT_ID 12     // uint: object id, 0 for the background
#define HMB_RESOLVE_BINDING_COUNT 13

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
