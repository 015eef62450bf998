#version 450
// One workgroup per large triangle (more than HMB_RASTER_LARGE_TILES tiles): its invocations
// write the triangle's (triangle, tile) pairs side by side into the range setup reserved, so
// a triangle covering the screen costs no single invocation more than a few pairs.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "raster_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;

layout(std430, binding = HMB_BIN_LARGE_BINDING_SETUP) readonly buffer Setup { SetupTriangle setup[]; };
layout(std430, binding = HMB_BIN_LARGE_BINDING_PAIRS) writeonly buffer Pairs { uvec2 pairs[]; };
layout(std430, binding = HMB_BIN_LARGE_BINDING_COUNTERS) readonly buffer Counters { RasterCounters counters; };
layout(std430, binding = HMB_BIN_LARGE_BINDING_LARGE) readonly buffer Large { uint large[]; };
layout(push_constant) uniform Params { RasterParams params; };

void main() {
  const uint entry = foldedGroupIndex();
  if (entry >= counters.largeCount) return;
  const uint slot = large[entry];
  const SetupTriangle s = setup[slot];
  const uvec2 tileFirst = s.pixelBounds.xy / HMB_RASTER_TILE;
  const uvec2 tileSpan = s.pixelBounds.zw / HMB_RASTER_TILE - tileFirst + 1u;
  const uint pairCount = tileSpan.x * tileSpan.y;
  for (uint i = gl_LocalInvocationID.x; i < pairCount; i += HMB_RASTER_GROUP) {
    const uvec2 tile = tileFirst + uvec2(i % tileSpan.x, i / tileSpan.x);
    pairs[s.firstPair + i] = uvec2(slot, tile.y * params.tilesX + tile.x);
  }
}
