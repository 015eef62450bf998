// What every post-process filter's gather binds (post_process_filter.h on the host): the layer
// to blur (its samples), its tiles' neighbour-max and the blurred output, at HMB_FILTER_BINDING_*.
#ifndef HMB_KERNELS_MBLUR_FILTER_BINDINGS_GLSL
#define HMB_KERNELS_MBLUR_FILTER_BINDINGS_GLSL

#include "mblur_layout.h"

#include "../shared/layer_layout.h"

// The layer's samples (colour, depth, velocity: shared/layer_layout.h).
layout(std430, binding = HMB_FILTER_BINDING_SAMPLES) readonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = HMB_FILTER_BINDING_NEIGHBOR_MAX) readonly buffer NeighborMax { vec4 neighborMax[]; };
layout(std430, binding = HMB_FILTER_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };

#endif
