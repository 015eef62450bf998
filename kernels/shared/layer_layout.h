// An image layer of per-pixel buffers (colour, normal and depth, velocity, object id) by device
// address: the G-buffer the resolve writes and the revealed layer the ray reveal writes, both
// read by the blur. One table instead of four bindings keeps each kernel within the storage
// buffers every device allows.
#ifndef HMB_KERNELS_SHARED_LAYER_LAYOUT_H
#define HMB_KERNELS_SHARED_LAYER_LAYOUT_H

#include "glsl_cpp.h"

#ifndef __cplusplus
layout(buffer_reference, std430, buffer_reference_align = 16) buffer LayerVec4s { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer LayerVec2s { vec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer LayerUints { uint v[]; };
#endif

HMB_GPU_BEGIN

struct LayerTable {
  HMB_REFERENCE(LayerVec4s) color;        // linear RGB, a = 1
  HMB_REFERENCE(LayerVec4s) normalDepth;  // xyz world normal, w camera-space depth
  HMB_REFERENCE(LayerVec2s) velocity;     // pixels per frame, y down
  HMB_REFERENCE(LayerUints) objectId;     // 0: the background
};

HMB_GPU_END

HMB_CHECK_SIZE(LayerTable, 32)

#endif
