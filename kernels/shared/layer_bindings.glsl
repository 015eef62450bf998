// An image layer as a kernel binds it: HMB_LAYER(name, firstBinding, access) declares layer
// `name` from binding firstBinding on, with access writeonly, readonly or nothing. The plain
// build binds its four buffers (colour, normal-depth, velocity, object id: HMB_LAYER_BINDINGS
// slots); builds with HMB_BIND_BY_ADDRESS (devices with few storage-buffer bindings) bind one
// LayerTable of their addresses. Either way a kernel reads and writes LAYER_COLOR(name, i),
// LAYER_NORMAL_DEPTH(name, i), LAYER_VELOCITY(name, i) and LAYER_OBJECT_ID(name, i).
#ifndef HMB_KERNELS_SHARED_LAYER_BINDINGS_GLSL
#define HMB_KERNELS_SHARED_LAYER_BINDINGS_GLSL

#include "layer_layout.h"

#ifdef HMB_BIND_BY_ADDRESS
#define HMB_LAYER(name, firstBinding, access) \
  layout(std430, binding = firstBinding) readonly buffer name##Table { LayerTable name; };
#define LAYER_COLOR(name, i) name.color.v[i]
#define LAYER_NORMAL_DEPTH(name, i) name.normalDepth.v[i]
#define LAYER_VELOCITY(name, i) name.velocity.v[i]
#define LAYER_OBJECT_ID(name, i) name.objectId.v[i]
#else
#define HMB_LAYER(name, firstBinding, access)                                                          \
  layout(std430, binding = firstBinding + 0) access buffer name##Color { vec4 name##ColorArray[]; };   \
  layout(std430, binding = firstBinding + 1) access buffer name##NormalDepth {                          \
    vec4 name##NormalDepthArray[];                                                                     \
  };                                                                                                   \
  layout(std430, binding = firstBinding + 2) access buffer name##Velocity { vec2 name##VelocityArray[]; }; \
  layout(std430, binding = firstBinding + 3) access buffer name##ObjectId { uint name##ObjectIdArray[]; };
#define LAYER_COLOR(name, i) name##ColorArray[i]
#define LAYER_NORMAL_DEPTH(name, i) name##NormalDepthArray[i]
#define LAYER_VELOCITY(name, i) name##VelocityArray[i]
#define LAYER_OBJECT_ID(name, i) name##ObjectIdArray[i]
#endif

#endif
