#version 450
// One invocation per (triangle, tile) pair: every covered pixel centre of the tile gets
// atomicMin(depth key << 32 | triangle id) in the visibility buffer (nearest
// first: raster_layout.h, depthKey). The current value is
// read first, so pixels already holding a nearer surface cost no atomic.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "raster_layout.h"
#include "../shared/indexing.glsl"
#include "raster_coverage.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;

layout(std430, binding = HMB_RASTERIZE_BINDING_SETUP) readonly buffer Setup { SetupTriangle setup[]; };
layout(std430, binding = HMB_RASTERIZE_BINDING_PAIRS) readonly buffer Pairs { uvec2 pairs[]; };
layout(std430, binding = HMB_RASTERIZE_BINDING_COUNTERS) readonly buffer Counters { RasterCounters counters; };
layout(std430, binding = HMB_RASTERIZE_BINDING_VISIBILITY) buffer Visibility { uint64_t visibility[]; };
layout(push_constant) uniform Params { RasterParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_RASTER_GROUP);
  if (i >= min(counters.pairCount, params.pairCapacity)) return;
  const uvec2 pair = pairs[i];
  const SetupTriangle s = setup[pair.x];
  uvec2 first, last;
  pairRectangle(s, pair.y, params.tilesX, first, last);
  const TriangleEdges edges = makeEdges(s);
  if (!rectangleMayBeCovered(edges, first, last)) return;
  for (uint y = first.y; y <= last.y; ++y) {
    for (uint x = first.x; x <= last.x; ++x) {
      const float depth = coverageDepth(s, edges, uvec2(x, y));
      if (depth < 0.0) continue;
      const uint index = y * params.width + x;
      const uint64_t candidate = (uint64_t(depthKey(depth)) << 32) | uint64_t(s.triangle);
      if (candidate < visibility[index]) atomicMin(visibility[index], candidate);
    }
  }
}
