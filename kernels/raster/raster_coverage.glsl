// Coverage and depth of one pixel centre in a set-up triangle, shared by both visibility
// schemes (64-bit atomics and the 32-bit two-pass fallback).
#ifndef HMB_KERNELS_RASTER_RASTER_COVERAGE_GLSL
#define HMB_KERNELS_RASTER_RASTER_COVERAGE_GLSL

bool lexLess(vec2 a, vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

// Edge function of a -> b at p, positive on the inside. Evaluated from the endpoints in a
// fixed order, so the two triangles sharing an edge get exactly opposite values: no pixel
// centre is covered twice or missed along a shared edge.
float edgeFunction(vec2 a, vec2 b, vec2 p) {
  if (lexLess(a, b)) return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
  return -((a.x - b.x) * (p.y - b.y) - (a.y - b.y) * (p.x - b.x));
}

// Top-left rule (y down, inside on the positive side): a centre exactly on an edge belongs
// to the triangle only if the edge is a top edge (horizontal, going right) or a left edge
// (going up).
bool ownsEdge(vec2 a, vec2 b) {
  const vec2 d = b - a;
  return (d.y == 0.0 && d.x > 0.0) || d.y < 0.0;
}

bool inside(float e, vec2 a, vec2 b) { return e > 0.0 || (e == 0.0 && ownsEdge(a, b)); }

// Depth (z/w) of the triangle at the pixel centre, or a negative value when not covered.
float coverageDepth(SetupTriangle s, uvec2 pixel) {
  const vec2 p = vec2(pixel) + 0.5;
  const float e0 = edgeFunction(s.p1, s.p2, p);
  const float e1 = edgeFunction(s.p2, s.p0, p);
  const float e2 = edgeFunction(s.p0, s.p1, p);
  if (!(inside(e0, s.p1, s.p2) && inside(e1, s.p2, s.p0) && inside(e2, s.p0, s.p1))) return -1.0;
  const float depth = (e0 * s.depth.x + e1 * s.depth.y + e2 * s.depth.z) / (e0 + e1 + e2);
  return (depth >= 0.0 && depth <= 1.0) ? depth : -1.0;
}

// The pixel rectangle of a (triangle, tile) pair: the tile clipped to the triangle's bounds.
void pairRectangle(SetupTriangle s, uint tile, uint tilesX, out uvec2 first, out uvec2 last) {
  const uvec2 origin = uvec2(tile % tilesX, tile / tilesX) * HMB_RASTER_TILE;
  first = max(origin, s.pixelBounds.xy);
  last = min(origin + HMB_RASTER_TILE - 1u, s.pixelBounds.zw);
}

#endif
