// An image layer as a kernel binds it, from its binding HMB_LAYER_BINDING on (defined by the
// including kernel, with HMB_LAYER_ACCESS: writeonly, readonly or nothing): colour,
// normal-depth, velocity and object id, or in builds with HMB_BIND_BY_ADDRESS one LayerTable
// of their addresses. Either way the kernel reads and writes layerColor[i], layerVelocity[i], ...
#ifndef HMB_KERNELS_SHARED_LAYER_BINDINGS_GLSL
#define HMB_KERNELS_SHARED_LAYER_BINDINGS_GLSL

#include "layer_layout.h"

#ifdef HMB_BIND_BY_ADDRESS
layout(std430, binding = HMB_LAYER_BINDING) readonly buffer Layer { LayerTable layer; };
#define layerColor layer.color.v
#define layerNormalDepth layer.normalDepth.v
#define layerVelocity layer.velocity.v
#define layerObjectId layer.objectId.v
#else
layout(std430, binding = HMB_LAYER_BINDING + 0) HMB_LAYER_ACCESS buffer LayerColor { vec4 layerColor[]; };
layout(std430, binding = HMB_LAYER_BINDING + 1) HMB_LAYER_ACCESS buffer LayerNormalDepth { vec4 layerNormalDepth[]; };
layout(std430, binding = HMB_LAYER_BINDING + 2) HMB_LAYER_ACCESS buffer LayerVelocity { vec2 layerVelocity[]; };
layout(std430, binding = HMB_LAYER_BINDING + 3) HMB_LAYER_ACCESS buffer LayerObjectId { uint layerObjectId[]; };
#endif

#endif
