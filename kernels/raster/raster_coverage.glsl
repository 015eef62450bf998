// Coverage and depth of pixel centres in a set-up triangle, shared by both visibility schemes
// (64-bit atomics and the 32-bit two-pass fallback). The plain C++ reference of this math is
// tests/raster/raster_reference.cpp: change both together.
#ifndef HMB_KERNELS_RASTER_RASTER_COVERAGE_GLSL
#define HMB_KERNELS_RASTER_RASTER_COVERAGE_GLSL

// One edge a -> b, evaluated from its lexicographically smaller endpoint `origin` with
// `direction` = other endpoint - origin, times `sign`. The two triangles sharing an edge build
// the same origin and direction, so their edge functions are exact negations: no pixel centre
// along a shared edge is covered twice or missed.
struct Edge {
  vec2 origin;
  vec2 direction;
  float sign;
  bool owned;  // top-left rule: a centre exactly on the edge is inside
};

// Top-left rule (y down, inside on the positive side): a top edge (horizontal, going right)
// or a left edge (going up) owns the centres exactly on it.
Edge makeEdge(vec2 a, vec2 b) {
  Edge e;
  const bool aFirst = a.x < b.x || (a.x == b.x && a.y < b.y);
  e.origin = aFirst ? a : b;
  e.direction = aFirst ? b - a : a - b;
  e.sign = aFirst ? 1.0 : -1.0;
  const vec2 d = b - a;
  e.owned = (d.y == 0.0 && d.x > 0.0) || d.y < 0.0;
  return e;
}

// `precise` here and in coverageDepth: no driver may fuse the products into multiply-adds, so
// every device computes the reference's values, rounded as it rounds them (Vulkan lets a
// driver fuse what is not `precise`; lavapipe does not here, a GPU driver may).
float edgeFunction(Edge e, vec2 p) {
  precise const float value = e.sign * (e.direction.x * (p.y - e.origin.y) - e.direction.y * (p.x - e.origin.x));
  return value;
}

bool insideEdge(Edge e, float value) { return value > 0.0 || (value == 0.0 && e.owned); }

struct TriangleEdges {
  Edge e0;  // p1 -> p2, weights p0
  Edge e1;  // p2 -> p0, weights p1
  Edge e2;  // p0 -> p1, weights p2
};

TriangleEdges makeEdges(SetupTriangle s) {
  TriangleEdges t;
  t.e0 = makeEdge(s.p1, s.p2);
  t.e1 = makeEdge(s.p2, s.p0);
  t.e2 = makeEdge(s.p0, s.p1);
  return t;
}

// Depth (z/w) of the triangle at the pixel centre, or a negative value when not covered.
float coverageDepth(SetupTriangle s, TriangleEdges t, uvec2 pixel) {
  const vec2 p = vec2(pixel) + 0.5;
  const float w0 = edgeFunction(t.e0, p);
  const float w1 = edgeFunction(t.e1, p);
  const float w2 = edgeFunction(t.e2, p);
  if (!(insideEdge(t.e0, w0) && insideEdge(t.e1, w1) && insideEdge(t.e2, w2))) return -1.0;
  precise const float depth = (w0 * s.depth.x + w1 * s.depth.y + w2 * s.depth.z) / (w0 + w1 + w2);
  return (depth >= 0.0 && depth <= 1.0) ? depth : -1.0;
}

// False only when every pixel centre of the rectangle lies clearly outside one edge (by more
// than a quarter pixel, far beyond rounding): such (triangle, tile) pairs skip the pixel loop.
bool edgeMayCover(Edge e, vec2 lo, vec2 hi) {
  const vec2 normal = e.sign * vec2(-e.direction.y, e.direction.x);  // gradient of the edge function
  const vec2 corner = vec2(normal.x >= 0.0 ? hi.x : lo.x, normal.y >= 0.0 ? hi.y : lo.y);
  return edgeFunction(e, corner) >= -0.25 * (abs(normal.x) + abs(normal.y));
}

bool rectangleMayBeCovered(TriangleEdges t, uvec2 first, uvec2 last) {
  const vec2 lo = vec2(first) + 0.5, hi = vec2(last) + 0.5;
  return edgeMayCover(t.e0, lo, hi) && edgeMayCover(t.e1, lo, hi) && edgeMayCover(t.e2, lo, hi);
}

// The pixel rectangle of a (triangle, tile) pair: the tile clipped to the triangle's bounds.
void pairRectangle(SetupTriangle s, uint tile, uint tilesX, out uvec2 first, out uvec2 last) {
  const uvec2 origin = uvec2(tile % tilesX, tile / tilesX) * HMB_RASTER_TILE;
  first = max(origin, s.pixelBounds.xy);
  last = min(origin + HMB_RASTER_TILE - 1u, s.pixelBounds.zw);
}

#endif
