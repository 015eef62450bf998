// Layout of gbuffer/resolve_gbuffer.comp: visibility buffer -> G-buffer.
#ifndef HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H
#define HMB_KERNELS_GBUFFER_GBUFFER_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_RESOLVE_GROUP_X 8
#define HMB_RESOLVE_GROUP_Y 8

#define HMB_RESOLVE_BINDING_VISIBILITY 0
#define HMB_RESOLVE_BINDING_TRIANGLES 1
#define HMB_RESOLVE_BINDING_INSTANCE_VERTICES 2
#define HMB_RESOLVE_BINDING_VERTICES 3
#define HMB_RESOLVE_BINDING_INSTANCES 4
#define HMB_RESOLVE_BINDING_MATERIALS 5
#define HMB_RESOLVE_BINDING_TEXELS 6
#define HMB_RESOLVE_BINDING_CAMERA 7
#define HMB_RESOLVE_BINDING_CLIP_CURRENT 8
#define HMB_RESOLVE_BINDING_CLIP_PREVIOUS 9
#define HMB_RESOLVE_BINDING_COLOR 10         // vec4: linear shaded colour, opaque (background colour where empty)
#define HMB_RESOLVE_BINDING_NORMAL_DEPTH 11  // vec4: xyz world normal, w camera-space depth
#define HMB_RESOLVE_BINDING_VELOCITY 12      // vec2: screen velocity, pixels per frame (y down)
#define HMB_RESOLVE_BINDING_OBJECT_ID 13     // uint: object id, 0 for the background
#define HMB_RESOLVE_BINDING_COUNT 14

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
