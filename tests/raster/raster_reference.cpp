// Plain C++ reference of kernels/raster/setup_triangles.comp and
// kernels/raster/raster_coverage.glsl: CHANGE IT TOGETHER WITH THOSE KERNELS. Every function
// below mirrors the GLSL function of the same name, statement by statement, in float.
// Built with -ffp-contract=off (tests/raster/CMakeLists.txt) so the host compiler adds no
// FMA of its own.
#include "tests/raster/raster_reference.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include "kernels/raster/clip_planes.h"

namespace hmb::test::reference {
namespace {

using glm::ivec2;
using glm::uvec2;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

// ---- setup_triangles.comp ----

// The clip volume is the kernels' own (kernels/raster/clip_planes.h).
using gpu::insideClipVolume;
using gpu::kMaxPolygon;
using gpu::kPlaneCount;
using gpu::planeDistance;

// Mirrors intersectEdge in clip_triangles.comp: from the endpoint inside the plane, divide
// before scaling (the kernel marks the expression `precise`, so no fused multiply-add).
vec4 intersectEdge(int plane, vec4 a, vec4 b) {
  float da = planeDistance(plane, a);
  float db = planeDistance(plane, b);
  if (!(da >= 0.0f)) {
    std::swap(a, b);
    std::swap(da, db);
  }
  const float denominator = da - db;
  vec4 point;
  for (int i = 0; i < 4; ++i) point[i] = a[i] + (b[i] - a[i]) / denominator * da;
  return point;
}

// GLSL round() leaves the direction of halfway cases to the implementation: lavapipe rounds
// half to even, as nearbyint does in the default rounding mode (checked by
// RasterizeKernelTest.HalfSubpixelVerticesSnapLikeTheReference).
float roundLikeDevice(float v) { return std::nearbyint(v); }

vec2 snapToScreen(vec4 c, uint32_t width, uint32_t height) {
  const vec2 ndc = vec2(c.x, c.y) / c.w;
  const vec2 screen = (ndc * 0.5f + 0.5f) * vec2(float(width), float(height));
  const vec2 scaled = screen * float(HMB_RASTER_SUBPIXEL);
  return vec2(roundLikeDevice(scaled.x), roundLikeDevice(scaled.y)) / float(HMB_RASTER_SUBPIXEL);
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

// GLSL int(float): out-of-range values are undefined there; C++ must not overflow. The
// emitted triangles lie inside the guard band, so this only guards the reference itself.
int toInt(float v) {
  if (!(v >= -2147483648.0f && v < 2147483648.0f)) return std::numeric_limits<int>::min();
  return static_cast<int>(v);
}

struct SetupState {
  uint32_t width, height;
  std::vector<gpu::SetupTriangle>* out;
  uint32_t pairCount = 0;
};

void emitTriangle(vec4 c0, vec4 c1, vec4 c2, uint32_t triangle, bool doubleSided, SetupState& state) {
  vec2 p0 = snapToScreen(c0, state.width, state.height), p1 = snapToScreen(c1, state.width, state.height),
       p2 = snapToScreen(c2, state.width, state.height);
  vec3 z = vec3(c0.z / c0.w, c1.z / c1.w, c2.z / c2.w);
  const float area = cross2(p1 - p0, p2 - p0);
  if (!(std::abs(area) > 0.0f) || std::isinf(area)) return;
  if (area > 0.0f && !doubleSided) return;
  if (area < 0.0f) {
    std::swap(p1, p2);
    z = vec3(z.x, z.z, z.y);
  }

  const vec2 lo = glm::min(p0, glm::min(p1, p2));
  const vec2 hi = glm::max(p0, glm::max(p1, p2));
  const ivec2 first = glm::max(ivec2(toInt(std::ceil(lo.x - 0.5f)), toInt(std::ceil(lo.y - 0.5f))), ivec2(0));
  const ivec2 last = glm::min(ivec2(toInt(std::floor(hi.x - 0.5f)), toInt(std::floor(hi.y - 0.5f))),
                              ivec2(int(state.width), int(state.height)) - 1);
  if (first.x > last.x || first.y > last.y) return;

  gpu::SetupTriangle s{};
  s.p0 = p0;
  s.p1 = p1;
  s.p2 = p2;
  s.triangle = triangle;
  s.firstPair = state.pairCount;
  s.depth = vec4(z, 0.0f);
  s.pixelBounds = uvec4(uvec2(first), uvec2(last));
  const uvec2 tileFirst = uvec2(first) / uint32_t(HMB_RASTER_TILE);
  const uvec2 tileSpan = uvec2(last) / uint32_t(HMB_RASTER_TILE) - tileFirst + 1u;
  state.pairCount += tileSpan.x * tileSpan.y;
  state.out->push_back(s);
}

bool isNanOrInf(vec4 v) {
  for (int i = 0; i < 4; ++i)
    if (std::isnan(v[i]) || std::isinf(v[i])) return true;
  return false;
}

void setupTriangle(std::span<const vec4> clip, const gpu::GpuTriangle& tri, uint32_t t, bool doubleSided,
                   SetupState& state) {
  // One slot more than the kernel so an overflow is detected instead of written past the end.
  vec4 polygon[kMaxPolygon + 1];
  polygon[0] = clip[tri.v0];
  polygon[1] = clip[tri.v1];
  polygon[2] = clip[tri.v2];
  for (int k = 0; k < 3; ++k)
    if (isNanOrInf(polygon[k])) return;

  const vec4 a = polygon[0], b = polygon[1], c = polygon[2];
  if ((a.x > a.w && b.x > b.w && c.x > c.w) || (a.x < -a.w && b.x < -b.w && c.x < -c.w) ||
      (a.y > a.w && b.y > b.w && c.y > c.w) || (a.y < -a.w && b.y < -b.w && c.y < -c.w) ||
      (a.z < 0.0f && b.z < 0.0f && c.z < 0.0f) || (a.z > a.w && b.z > b.w && c.z > c.w))
    return;

  if (insideClipVolume(a) && insideClipVolume(b) && insideClipVolume(c)) {
    emitTriangle(a, b, c, t, doubleSided, state);
    return;
  }

  int count = 3;
  for (int plane = 0; plane < kPlaneCount; ++plane) {
    bool allInside = true;
    for (int k = 0; k < count; ++k) allInside = allInside && planeDistance(plane, polygon[k]) >= 0.0f;
    if (allInside) continue;
    vec4 clipped[kMaxPolygon + 2];
    int clippedCount = 0;
    for (int k = 0; k < count; ++k) {
      const vec4 current = polygon[k];
      const vec4 next = polygon[(k + 1) % count];
      const bool currentInside = planeDistance(plane, current) >= 0.0f;
      const bool nextInside = planeDistance(plane, next) >= 0.0f;
      if (currentInside) clipped[clippedCount++] = current;
      if (currentInside != nextInside) clipped[clippedCount++] = intersectEdge(plane, current, next);
      if (clippedCount > kMaxPolygon)
        throw std::logic_error("triangle " + std::to_string(t) + ": clipping against plane " + std::to_string(plane) +
                               " needs more than " + std::to_string(kMaxPolygon) +
                               " polygon vertices (setup_triangles.comp would write past its arrays)");
    }
    count = clippedCount;
    for (int k = 0; k < count; ++k) polygon[k] = clipped[k];
    if (count < 3) return;
  }
  for (int k = 1; k + 1 < count; ++k) emitTriangle(polygon[0], polygon[k], polygon[k + 1], t, doubleSided, state);
}

// ---- raster_coverage.glsl ----

struct Edge {
  vec2 origin;
  vec2 direction;
  float sign;
  bool owned;
};

Edge makeEdge(vec2 a, vec2 b) {
  Edge e;
  const bool aFirst = a.x < b.x || (a.x == b.x && a.y < b.y);
  e.origin = aFirst ? a : b;
  e.direction = aFirst ? b - a : a - b;
  e.sign = aFirst ? 1.0f : -1.0f;
  const vec2 d = b - a;
  e.owned = (d.y == 0.0f && d.x > 0.0f) || d.y < 0.0f;
  return e;
}

float edgeFunction(const Edge& e, vec2 p) {
  return e.sign * (e.direction.x * (p.y - e.origin.y) - e.direction.y * (p.x - e.origin.x));
}

bool insideEdge(const Edge& e, float value) { return value > 0.0f || (value == 0.0f && e.owned); }

}  // namespace

uint32_t tilesAcross(uint32_t pixels) { return (pixels + HMB_RASTER_TILE - 1) / HMB_RASTER_TILE; }

std::vector<gpu::SetupTriangle> setupTriangles(std::span<const glm::vec4> clip,
                                               std::span<const gpu::GpuTriangle> triangles,
                                               const std::vector<bool>& doubleSided, uint32_t width,
                                               uint32_t height) {
  std::vector<gpu::SetupTriangle> out;
  SetupState state{width, height, &out};
  for (size_t t = 0; t < triangles.size(); ++t) {
    const gpu::GpuTriangle& tri = triangles[t];
    setupTriangle(clip, tri, static_cast<uint32_t>(t), doubleSided.at(tri.instance), state);
  }
  return out;
}

std::vector<uint32_t> triangleTiles(const gpu::SetupTriangle& s, uint32_t tilesX) {
  const uvec2 tileFirst = uvec2(s.pixelBounds.x, s.pixelBounds.y) / uint32_t(HMB_RASTER_TILE);
  const uvec2 tileSpan = uvec2(s.pixelBounds.z, s.pixelBounds.w) / uint32_t(HMB_RASTER_TILE) - tileFirst + 1u;
  std::vector<uint32_t> tiles;
  tiles.reserve(size_t(tileSpan.x) * tileSpan.y);
  for (uint32_t i = 0; i < tileSpan.x * tileSpan.y; ++i) {
    const uvec2 tile = tileFirst + uvec2(i % tileSpan.x, i / tileSpan.x);
    tiles.push_back(tile.y * tilesX + tile.x);
  }
  return tiles;
}

float coverageDepth(const gpu::SetupTriangle& s, glm::uvec2 pixel) {
  const Edge e0 = makeEdge(s.p1, s.p2), e1 = makeEdge(s.p2, s.p0), e2 = makeEdge(s.p0, s.p1);
  const vec2 p = vec2(pixel) + 0.5f;
  const float w0 = edgeFunction(e0, p);
  const float w1 = edgeFunction(e1, p);
  const float w2 = edgeFunction(e2, p);
  if (!(insideEdge(e0, w0) && insideEdge(e1, w1) && insideEdge(e2, w2))) return -1.0f;
  const float depth = (w0 * s.depth.x + w1 * s.depth.y + w2 * s.depth.z) / (w0 + w1 + w2);
  return (depth >= 0.0f && depth <= 1.0f) ? depth : -1.0f;
}

ReferenceVisibility rasterizeReference(std::span<const gpu::SetupTriangle> setup, uint32_t width, uint32_t height) {
  ReferenceVisibility out;
  out.width = width;
  out.height = height;
  out.entries.assign(size_t(width) * height, uvec2(HMB_VIS_EMPTY));
  out.coverage.assign(size_t(width) * height, 0u);
  for (const gpu::SetupTriangle& s : setup) {
    const uvec4 b = s.pixelBounds;
    if (b.z >= width || b.w >= height)
      throw std::logic_error("set-up triangle " + std::to_string(s.triangle) + " has pixel bounds outside the image");
    for (uint32_t y = b.y; y <= b.w; ++y) {
      for (uint32_t x = b.x; x <= b.z; ++x) {
        const float depth = coverageDepth(s, uvec2(x, y));
        if (depth < 0.0f) continue;
        const size_t index = size_t(y) * width + x;
        ++out.coverage[index];
        const uint32_t key = gpu::depthKey(depth);
        const uint64_t candidate = (uint64_t(key) << 32) | s.triangle;
        const uint64_t current = (uint64_t(out.entries[index].y) << 32) | out.entries[index].x;
        if (candidate < current) out.entries[index] = uvec2(s.triangle, key);
      }
    }
  }
  return out;
}

bool setupLess(const gpu::SetupTriangle& a, const gpu::SetupTriangle& b) {
  return std::tie(a.triangle, a.p0.x, a.p0.y, a.p1.x, a.p1.y, a.p2.x, a.p2.y) <
         std::tie(b.triangle, b.p0.x, b.p0.y, b.p1.x, b.p1.y, b.p2.x, b.p2.y);
}

}  // namespace hmb::test::reference
