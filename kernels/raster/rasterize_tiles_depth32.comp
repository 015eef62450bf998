#version 450
// The visibility buffer without 64-bit atomics, in two passes over the same pairs: pass 0
// takes atomicMin of the depth keys (raster_layout.h, depthKey); pass 1 writes the triangle id where the depth matches
// (atomicMin on the id, so equal depths resolve to the same triangle as the 64-bit path).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "raster_layout.h"
#include "../shared/indexing.glsl"
#include "raster_coverage.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;

layout(std430, binding = HMB_RASTERIZE_BINDING_SETUP) readonly buffer Setup { SetupTriangle setup[]; };
layout(std430, binding = HMB_RASTERIZE_BINDING_PAIRS) readonly buffer Pairs { uvec2 pairs[]; };
layout(std430, binding = HMB_RASTERIZE_BINDING_COUNTERS) readonly buffer Counters { RasterCounters counters; };
// Entry i is uvec2(triangle id, depth key): the same bytes as the 64-bit scheme's uint64.
layout(std430, binding = HMB_RASTERIZE_BINDING_VISIBILITY) buffer Visibility { uint visibility[]; };
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
      const uint key = depthKey(depth);
      if (params.pass == 0u) {
        if (key < visibility[2u * index + 1u]) atomicMin(visibility[2u * index + 1u], key);
      } else if (key == visibility[2u * index + 1u]) {
        atomicMin(visibility[2u * index], s.triangle);
      }
    }
  }
}
