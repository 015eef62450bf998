// How the compute rasterizer resolves visibility (a device's choice, reported with every frame)
// and what a frame's raster did: the rasterizer's facts a render's result and report carry.
#pragma once

#include <cstdint>

namespace hmb::passes {

enum class VisibilityScheme {
  Int64Atomics,    // one atomicMin of (depth key << 32 | triangle id) per covered pixel
  Depth32TwoPass,  // without shaderBufferInt64Atomics: atomicMin depth, then id where depth matches
  // CPU devices: each tile's pairs linked into a list, one invocation per tile keeps its 64
  // pixels' nearest surface in registers and writes them once (kernels/raster/rasterize_tile_lists.comp)
  TileLists,
};

const char* visibilitySchemeName(VisibilityScheme scheme);
// Every pass the rasterizer's plan leaves out because of its scheme (the device's choice, not
// the frame's content) gives a reason that starts with this.
inline constexpr const char* kVisibilitySchemeReason = "visibility scheme ";

// What the last frame's counters said (read after the frame by growIfOverflowed()).
struct RasterStats {
  uint32_t setupTriangles = 0;  // triangles left after culling and clipping (clipping may add)
  uint32_t tilePairs = 0;       // (triangle, tile) pairs rasterized
  uint32_t largeTriangles = 0;  // triangles binned by bin_large_triangles
  uint32_t clippedTriangles = 0;  // triangles that crossed the near plane or the guard band
  uint32_t regrowths = 0;       // times the buffers grew since this pass was created
};

}  // namespace hmb::passes
