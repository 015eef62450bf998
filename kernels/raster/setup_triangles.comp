#version 450
// Per scene triangle: frustum cull, clip against the near plane and a guard band (so snapped
// screen coordinates stay exact in float), snap to the sub-pixel grid, cull back faces of
// single-sided materials and zero-area triangles, then bin: one (triangle, tile) pair per
// screen tile its pixel bounds touch (large triangles leave that to bin_large_triangles).
#extension GL_GOOGLE_include_directive : require
#include "raster_layout.h"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;

layout(std430, binding = HMB_SETUP_BINDING_TRIANGLES) readonly buffer Triangles { GpuTriangle triangles[]; };
layout(std430, binding = HMB_SETUP_BINDING_INSTANCES) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = HMB_SETUP_BINDING_CLIP_CURRENT) readonly buffer ClipCurrent { vec4 clipCurrent[]; };
layout(std430, binding = HMB_SETUP_BINDING_SETUP) writeonly buffer Setup { SetupTriangle setup[]; };
layout(std430, binding = HMB_SETUP_BINDING_PAIRS) writeonly buffer Pairs { uvec2 pairs[]; };
layout(std430, binding = HMB_SETUP_BINDING_COUNTERS) buffer Counters { RasterCounters counters; };
layout(std430, binding = HMB_SETUP_BINDING_LARGE) writeonly buffer Large { uint large[]; };
layout(push_constant) uniform Params { RasterParams params; };

// Clip planes as dot(plane, clip) >= 0: near (z >= 0) and a guard band of 4x the viewport.
const float kGuardBand = 4.0;
const int kPlaneCount = 5;
const int kMaxPolygon = 3 + kPlaneCount;

float planeDistance(int plane, vec4 c) {
  switch (plane) {
    case 0: return c.z;
    case 1: return kGuardBand * c.w - c.x;
    case 2: return kGuardBand * c.w + c.x;
    case 3: return kGuardBand * c.w - c.y;
    default: return kGuardBand * c.w + c.y;
  }
}

// planeDistance(plane, c) >= 0 for every plane (the same comparisons, without the arrays).
bool insideClipVolume(vec4 c) {
  return c.z >= 0.0 && abs(c.x) <= kGuardBand * c.w && abs(c.y) <= kGuardBand * c.w;
}

// The intersection of an edge with a plane, interpolated from the endpoint inside the plane:
// the choice depends only on the edge and the plane, so two triangles sharing the edge get the
// very same point (no cracks after clipping), and dividing before scaling keeps the point
// exact enough when the outside endpoint is astronomically far (t = da / (da - db) would
// round to 1 and return the outside endpoint itself). `precise`: no fused multiply-add, so
// the C++ reference (tests/raster/raster_reference.cpp) gets the same bits.
vec4 intersectEdge(int plane, vec4 a, vec4 b) {
  float da = planeDistance(plane, a);
  float db = planeDistance(plane, b);
  if (!(da >= 0.0)) {
    const vec4 t = a; a = b; b = t;
    const float d = da; da = db; db = d;
  }
  precise const vec4 point = a + (b - a) / (da - db) * da;
  return point;
}

vec2 snapToScreen(vec4 c) {
  const vec2 ndc = c.xy / c.w;
  const vec2 screen = (ndc * 0.5 + 0.5) * vec2(params.width, params.height);
  return round(screen * HMB_RASTER_SUBPIXEL) / HMB_RASTER_SUBPIXEL;
}

float cross2(vec2 a, vec2 b) { return a.x * b.y - a.y * b.x; }

void emitTriangle(vec4 c0, vec4 c1, vec4 c2, uint triangle, bool doubleSided) {
  vec2 p0 = snapToScreen(c0), p1 = snapToScreen(c1), p2 = snapToScreen(c2);
  vec3 z = vec3(c0.z / c0.w, c1.z / c1.w, c2.z / c2.w);
  const float area = cross2(p1 - p0, p2 - p0);
  if (!(area != 0.0)) return;  // zero area (or NaN from degenerate input)
  // With y pointing down the image, faces counter-clockwise in the y-up view (glTF front
  // faces) have negative area here.
  if (area > 0.0 && !doubleSided) return;
  if (area < 0.0) {  // make the inside the positive side of every edge
    const vec2 t = p1; p1 = p2; p2 = t;
    z = z.xzy;
  }

  const vec2 lo = min(p0, min(p1, p2));
  const vec2 hi = max(p0, max(p1, p2));
  // Pixel centres (x + 0.5) inside the bounds, clamped to the image.
  const ivec2 first = max(ivec2(ceil(lo - 0.5)), ivec2(0));
  const ivec2 last = min(ivec2(floor(hi - 0.5)), ivec2(params.width, params.height) - 1);
  if (first.x > last.x || first.y > last.y) return;

  const uvec2 tileFirst = uvec2(first) / HMB_RASTER_TILE;
  const uvec2 tileSpan = uvec2(last) / HMB_RASTER_TILE - tileFirst + 1u;
  const uint pairCount = tileSpan.x * tileSpan.y;

  const uint slot = atomicAdd(counters.setupCount, 1u);
  const uint base = atomicAdd(counters.pairCount, pairCount);
  uint overflow = slot >= params.setupCapacity ? HMB_RASTER_OVERFLOW_SETUP : 0u;
  if (base + pairCount < base) overflow |= HMB_RASTER_OVERFLOW_PAIRS_WRAPPED;
  else if (base + pairCount > params.pairCapacity) overflow |= HMB_RASTER_OVERFLOW_PAIRS;
  if (overflow != 0u) {
    atomicOr(counters.overflow, overflow);
    return;
  }
  setup[slot].p0 = p0;
  setup[slot].p1 = p1;
  setup[slot].p2 = p2;
  setup[slot].triangle = triangle;
  setup[slot].firstPair = base;
  setup[slot].depth = vec4(z, 0.0);
  setup[slot].pixelBounds = uvec4(first, last);

  if (pairCount > HMB_RASTER_LARGE_TILES) {
    // Many tiles: a workgroup of bin_large_triangles writes them, not this one invocation.
    large[atomicAdd(counters.largeCount, 1u)] = slot;  // largeCount <= setupCount: fits
    return;
  }
  for (uint i = 0u; i < pairCount; ++i) {
    const uvec2 tile = tileFirst + uvec2(i % tileSpan.x, i / tileSpan.x);
    pairs[base + i] = uvec2(slot, tile.y * params.tilesX + tile.x);
  }
}

void main() {
  const uint t = linearInvocationIndex(HMB_RASTER_GROUP);
  if (t >= params.triangleCount) return;
  const GpuTriangle tri = triangles[t];
  const bool doubleSided = (instances[tri.instance].flags & HMB_INSTANCE_DOUBLE_SIDED) != 0u;
  vec4 polygon[kMaxPolygon];
  polygon[0] = clipCurrent[tri.v0];
  polygon[1] = clipCurrent[tri.v1];
  polygon[2] = clipCurrent[tri.v2];
  for (int k = 0; k < 3; ++k)
    if (any(isnan(polygon[k])) || any(isinf(polygon[k]))) return;

  // Trivial reject: all three vertices outside one frustum plane (x, y within w; z within [0, w]).
  const vec4 a = polygon[0], b = polygon[1], c = polygon[2];
  if ((a.x > a.w && b.x > b.w && c.x > c.w) || (a.x < -a.w && b.x < -b.w && c.x < -c.w) ||
      (a.y > a.w && b.y > b.w && c.y > c.w) || (a.y < -a.w && b.y < -b.w && c.y < -c.w) ||
      (a.z < 0.0 && b.z < 0.0 && c.z < 0.0) || (a.z > a.w && b.z > b.w && c.z > c.w))
    return;

  // Most triangles need no clipping: skip the polygon arrays, which CPU devices keep in memory.
  if (insideClipVolume(a) && insideClipVolume(b) && insideClipVolume(c)) {
    emitTriangle(a, b, c, t, doubleSided);
    return;
  }

  int count = 3;
  for (int plane = 0; plane < kPlaneCount; ++plane) {
    bool allInside = true;
    for (int k = 0; k < count; ++k) allInside = allInside && planeDistance(plane, polygon[k]) >= 0.0;
    if (allInside) continue;
    vec4 clipped[kMaxPolygon];
    int clippedCount = 0;
    for (int k = 0; k < count; ++k) {
      const vec4 current = polygon[k];
      const vec4 next = polygon[(k + 1) % count];
      const bool currentInside = planeDistance(plane, current) >= 0.0;
      const bool nextInside = planeDistance(plane, next) >= 0.0;
      if (currentInside) clipped[clippedCount++] = current;
      if (currentInside != nextInside) clipped[clippedCount++] = intersectEdge(plane, current, next);
    }
    count = clippedCount;
    for (int k = 0; k < count; ++k) polygon[k] = clipped[k];
    if (count < 3) return;
  }
  // A convex polygon: fan from the first vertex keeps the winding of the input triangle.
  for (int k = 1; k + 1 < count; ++k) emitTriangle(polygon[0], polygon[k], polygon[k + 1], t, doubleSided);
}
