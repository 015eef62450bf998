#version 450
// Sizes the indirect dispatches that follow setup, folded into rows of at most 65535 groups.
// Pass 0 (after setup_triangles): clip_triangles, one invocation per listed triangle. Pass 1
// (after clip_triangles): bin_large_triangles (one workgroup per large triangle) and
// rasterize_tiles (one invocation per (triangle, tile) pair).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "raster_layout.h"
#include "../shared/dispatch.h"

layout(local_size_x = 1) in;

layout(std430, binding = HMB_SIZE_DISPATCH_BINDING_COUNTERS) buffer Counters { RasterCounters counters; };
layout(push_constant) uniform Params { RasterParams params; };

void main() {
  if (params.pass == 0u) {
    const uint listed = min(counters.clipCount, params.clipCapacity);
    const uvec3 clip = foldedGroups((listed + HMB_RASTER_GROUP - 1u) / HMB_RASTER_GROUP);
    counters.clipX = clip.x;
    counters.clipY = clip.y;
    counters.clipZ = clip.z;
    return;
  }
  // After an overflow nothing is rasterized: the host grows the buffers and renders again.
  const bool overflow = counters.overflow != 0u;
  const uint pairs = overflow ? 0u : counters.pairCount;
  const uint large = overflow ? 0u : counters.largeCount;
  const uvec3 rasterize = foldedGroups((pairs + HMB_RASTER_GROUP - 1u) / HMB_RASTER_GROUP);
  const uvec3 binLarge = foldedGroups(large);
  counters.rasterizeX = rasterize.x;
  counters.rasterizeY = rasterize.y;
  counters.rasterizeZ = rasterize.z;
  counters.binLargeX = binLarge.x;
  counters.binLargeY = binLarge.y;
  counters.binLargeZ = binLarge.z;
}
