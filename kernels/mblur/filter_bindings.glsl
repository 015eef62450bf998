// What every post-process filter's gather binds (post_process_filter.h on the host): the layer
// to blur (its samples), its tiles' neighbour-max and the blurred output, at HMB_FILTER_BINDING_*.
#ifndef HMB_KERNELS_MBLUR_FILTER_BINDINGS_GLSL
#define HMB_KERNELS_MBLUR_FILTER_BINDINGS_GLSL

#include "mblur_layout.h"

#include "../shared/layer_layout.h"

// The layer's samples (colour, depth, velocity: shared/layer_layout.h) and the tiles'
// neighbour-max velocities are read at per-pixel addresses, as uniform texel buffers
// (shared/texel_records.glsl).
#include "../shared/texel_records.glsl"
layout(binding = HMB_FILTER_BINDING_SAMPLES) uniform utextureBuffer sampleTexels;
layout(binding = HMB_FILTER_BINDING_NEIGHBOR_MAX) uniform utextureBuffer neighborMaxTexels;
layout(std430, binding = HMB_FILTER_BINDING_OUTPUT) writeonly buffer Output { vec4 outColor[]; };
// Each pixel's path over the shutter (gbuffer_layout.h: uvec2 per pixel), read where the
// gather takes the curved path; any buffer when it does not.
layout(binding = HMB_FILTER_BINDING_SHUTTER_PATHS) uniform utextureBuffer shutterPathTexels;

uvec4 layerSampleAt(uint i) { return recordAt(sampleTexels, i); }
vec4 neighborMaxAt(uint tile) { return floatRecordAt(neighborMaxTexels, tile); }
uvec2 shutterPathAt(uint i) { return halfRecordAt(shutterPathTexels, i); }

#endif
