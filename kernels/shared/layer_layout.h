// An image layer of per-pixel buffers (colour, normal and depth, velocity, object id): the
// G-buffer the resolve writes and the revealed layer the ray reveal writes, both read by the
// blur. Its LayerTable of addresses takes one binding instead of four on devices with few
// storage-buffer bindings (shared/layer_bindings.glsl).
#ifndef HMB_KERNELS_SHARED_LAYER_LAYOUT_H
#define HMB_KERNELS_SHARED_LAYER_LAYOUT_H

#include "glsl_cpp.h"

#ifdef HMB_ADDRESS_TABLES
#ifndef __cplusplus
layout(buffer_reference, std430, buffer_reference_align = 16) buffer LayerVec4sRef { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 8) buffer LayerVec2sRef { vec2 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer LayerUintsRef { uint v[]; };
#endif

HMB_GPU_BEGIN

struct LayerTable {
  HMB_REFERENCE(LayerVec4sRef) color;        // linear RGB, a = 1
  HMB_REFERENCE(LayerVec4sRef) normalDepth;  // xyz world normal, w camera-space depth
  HMB_REFERENCE(LayerVec2sRef) velocity;     // pixels per frame, y down
  HMB_REFERENCE(LayerUintsRef) objectId;     // 0: the background
};

HMB_GPU_END

HMB_CHECK_SIZE(LayerTable, 32)
#endif

// A layer takes 4 binding numbers (shared/layer_bindings.glsl); HMB_BIND_BY_ADDRESS builds bind
// one table at the first and leave the others unused, keeping the numbers after it.
#define HMB_LAYER_BINDINGS 4

#endif
