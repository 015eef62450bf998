#version 450
// The tile-lists scheme, for CPU devices: one invocation per 8x8 screen tile walks its tile's
// list of (triangle, tile) pairs (link_tile_pairs) and keeps the nearest surface of each of its
// 64 pixel centres in registers, then writes all 64 once. No atomics, no clear (every entry is
// written) and no 64-bit types: the entries are the same (triangle id, depth key) words the
// int64-atomics scheme's atomicMin leaves.
// Why CPU devices only: a CPU runs the 64 pixels as straight-line vector code over several
// tiles at once, with the state in registers and on the stack. A GPU lane would hold 128 live
// registers here; there a workgroup per tile with a lane per pixel is the shape, and the
// renderer keeps the atomic schemes for GPUs (rasterize_pass.cpp, defaultVisibilityScheme).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#extension GL_EXT_control_flow_attributes : require
#include "raster_layout.h"
#include "../shared/indexing.glsl"
#include "raster_coverage.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;

layout(std430, binding = HMB_TILE_LISTS_BINDING_SETUP) readonly buffer Setup { SetupTriangle setup[]; };
layout(std430, binding = HMB_TILE_LISTS_BINDING_PAIRS) readonly buffer Pairs { uvec2 pairs[]; };
layout(std430, binding = HMB_TILE_LISTS_BINDING_HEADS) readonly buffer Heads { uint heads[]; };
// Entry i is uvec2(triangle id, depth key), as the other schemes write it.
layout(std430, binding = HMB_TILE_LISTS_BINDING_VISIBILITY) writeonly buffer Visibility { uvec2 visibility[]; };
layout(std430, binding = HMB_TILE_LISTS_BINDING_COUNTERS) buffer Counters { RasterCounters counters; };
layout(push_constant) uniform Params { RasterParams params; };

const uint kPixels = HMB_RASTER_TILE * HMB_RASTER_TILE;

void main() {
  const uint tile = linearInvocationIndex(HMB_RASTER_GROUP);
  const uint tilesY = (params.height + HMB_RASTER_TILE - 1u) / HMB_RASTER_TILE;
  if (tile >= params.tilesX * tilesY) return;
  const uvec2 origin = uvec2(tile % params.tilesX, tile / params.tilesX) * HMB_RASTER_TILE;

  // The nearest (depth key, triangle id) per pixel, compared as the 64-bit atomicMin compares
  // (key << 32 | id): the smaller key, then the smaller id. Starts empty.
  uint nearestKey[kPixels];
  uint nearestId[kPixels];
  [[unroll]] for (uint k = 0u; k < kPixels; ++k) {
    nearestKey[k] = HMB_VIS_EMPTY;
    nearestId[k] = HMB_VIS_EMPTY;
  }
  uint p = heads[tile];
  while (p != HMB_TILE_LIST_END) {
    const uvec2 pair = pairs[p];  // (set-up triangle, next pair of this tile)
    const SetupTriangle s = setup[pair.x];
    const TriangleEdges edges = makeEdges(s);
    [[unroll]] for (uint k = 0u; k < kPixels; ++k) {
      const uvec2 pixel = origin + uvec2(k % HMB_RASTER_TILE, k / HMB_RASTER_TILE);
      const float depth = coverageDepth(s, edges, pixel);
      const bool inBounds = all(greaterThanEqual(pixel, s.pixelBounds.xy)) && all(lessThanEqual(pixel, s.pixelBounds.zw));
      const uint key = depthKey(depth);
      const bool nearer = key < nearestKey[k] || (key == nearestKey[k] && s.triangle < nearestId[k]);
      if (depth >= 0.0 && inBounds && nearer) {
        nearestKey[k] = key;
        nearestId[k] = s.triangle;
      }
    }
    p = pair.y;
  }
  // Only an ended loop leaves the list unfinished: a tile of 65535 triangles or more on
  // llvmpipe. Its pixels are written anyway; the host refuses the frame.
  if (p != HMB_TILE_LIST_END) atomicOr(counters.overflow, HMB_RASTER_OVERFLOW_TILE_LIST);
  [[unroll]] for (uint k = 0u; k < kPixels; ++k) {
    const uvec2 pixel = origin + uvec2(k % HMB_RASTER_TILE, k / HMB_RASTER_TILE);
    if (pixel.x < params.width && pixel.y < params.height)
      visibility[pixel.y * params.width + pixel.x] = uvec2(nearestId[k], nearestKey[k]);
  }
}
