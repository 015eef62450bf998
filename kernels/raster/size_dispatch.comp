#version 450
// Turns the number of (triangle, tile) pairs the setup produced into the indirect dispatch of
// rasterize_tiles, folded into rows of at most 65535 groups.
#extension GL_GOOGLE_include_directive : require
#include "raster_layout.h"

layout(local_size_x = 1) in;

layout(std430, binding = 0) buffer Counters { RasterCounters counters; };
layout(push_constant) uniform Params { RasterParams params; };

void main() {
  const uint pairs = min(counters.pairCount, params.pairCapacity);
  const uint groups = (pairs + HMB_RASTER_GROUP - 1u) / HMB_RASTER_GROUP;
  counters.dispatchX = min(groups, 65535u);
  counters.dispatchY = groups == 0u ? 0u : (groups + 65534u) / 65535u;
  counters.dispatchZ = 1u;
}
