// What every post-process filter's gather binds (post_process_filter.h on the host): the layer
// to blur, its tiles' neighbour-max and the blurred output, at HMB_FILTER_BINDING_*.
#ifndef HMB_KERNELS_MBLUR_FILTER_BINDINGS_GLSL
#define HMB_KERNELS_MBLUR_FILTER_BINDINGS_GLSL

#include "mblur_layout.h"

layout(std430, binding = HMB_FILTER_BINDING_COLOR) readonly buffer Color { vec4 color[]; };
layout(std430, binding = HMB_FILTER_BINDING_NORMAL_DEPTH) readonly buffer NormalDepth { vec4 normalDepth[]; };
layout(std430, binding = HMB_FILTER_BINDING_VELOCITY) readonly buffer Velocity { vec2 velocity[]; };
layout(std430, binding = HMB_FILTER_BINDING_NEIGHBOR_MAX) readonly buffer NeighborMax { vec4 neighborMax[]; };
layout(std430, binding = HMB_FILTER_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };

#endif
