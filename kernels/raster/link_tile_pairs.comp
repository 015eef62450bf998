#version 450
// The tile-lists scheme's binning: one invocation per (triangle, tile) pair pushes the pair on
// its tile's list (one atomic exchange), overwriting the pair's tile with the next pair, so
// rasterize_tile_lists can walk every pair of one tile.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "raster_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;

layout(std430, binding = HMB_LINK_BINDING_PAIRS) buffer Pairs { uvec2 pairs[]; };
layout(std430, binding = HMB_LINK_BINDING_COUNTERS) readonly buffer Counters { RasterCounters counters; };
layout(std430, binding = HMB_LINK_BINDING_HEADS) buffer Heads { uint heads[]; };
layout(push_constant) uniform Params { RasterParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_RASTER_GROUP);
  // After an overflow some slots below the capacity were reserved but never written: link
  // nothing (the lists stay empty) and let the host grow the buffers and record the frame again.
  if (counters.overflow != 0u || i >= min(counters.pairCount, params.pairCapacity)) return;
  const uint tile = pairs[i].y;
  pairs[i].y = atomicExchange(heads[tile], i);
}
