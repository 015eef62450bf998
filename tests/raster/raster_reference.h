// Plain C++ reference of the compute rasterizer's math: setup (frustum reject, near-plane and
// guard-band clipping, snapping, culling, pixel bounds, binning) and per-pixel coverage and
// depth. It mirrors kernels/raster/setup_triangles.comp and kernels/raster/raster_coverage.glsl
// line by line in float, so it matches the kernels bit for bit except where the device
// contracts a*b - c*d into an FMA: CHANGE IT TOGETHER WITH THOSE KERNELS.
//
// Differences that are deliberate: the reference writes setup triangles in a deterministic
// order (by triangle id, then clip-fan order) where the kernel's order follows its atomics,
// and it rasterizes every pixel of a triangle's bounds (no conservative tile reject), so a
// reject that is not conservative shows up as a disagreement.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/raster/raster_layout.h"
#include "kernels/shared/scene_layout.h"

namespace hmb::test::reference {

// What setup_triangles writes, in triangle-id and clip-fan order. firstPair is the prefix sum
// of the tile counts in this order (the kernel's value depends on the order of its atomics).
// doubleSided is per instance (GpuTriangle::instance indexes it).
// Throws std::logic_error when clipping would need more polygon vertices than the kernel's
// local arrays hold (the kernel would write out of bounds).
std::vector<gpu::SetupTriangle> setupTriangles(std::span<const glm::vec4> clip,
                                               std::span<const gpu::GpuTriangle> triangles,
                                               const std::vector<bool>& doubleSided, uint32_t width,
                                               uint32_t height);

// Screen tiles (HMB_RASTER_TILE pixels) across the image, as the host passes in RasterParams.
uint32_t tilesAcross(uint32_t pixels);

// The tile indices (tile.y * tilesX + tile.x) of a set-up triangle's pixel bounds, row by row:
// the order in which setup_triangles / bin_large_triangles write its (triangle, tile) pairs.
std::vector<uint32_t> triangleTiles(const gpu::SetupTriangle& s, uint32_t tilesX);

// coverageDepth() of raster_coverage.glsl: z/w at the pixel centre, or -1 when the centre is
// not covered (or the depth is outside [0, 1]).
float coverageDepth(const gpu::SetupTriangle& s, glm::uvec2 pixel);

struct ReferenceVisibility {
  uint32_t width = 0, height = 0;
  std::vector<glm::uvec2> entries;  // (triangle id, depth key), HMB_VIS_EMPTY in both when empty
  std::vector<uint32_t> coverage;   // set-up triangles whose coverageDepth() >= 0 at the centre

  uint32_t idAt(uint32_t x, uint32_t y) const { return entries[size_t(y) * width + x].x; }
};

// The visibility buffer: per pixel the smallest (depth key, triangle id) over the set-up
// triangles covering its centre, as both visibility schemes compute it.
ReferenceVisibility rasterizeReference(std::span<const gpu::SetupTriangle> setup, uint32_t width, uint32_t height);

// Strict weak order used to compare setup outputs as sets: triangle, then p0, p1, p2.
bool setupLess(const gpu::SetupTriangle& a, const gpu::SetupTriangle& b);

}  // namespace hmb::test::reference
