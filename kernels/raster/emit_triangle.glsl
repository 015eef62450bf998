// The end of triangle setup, shared by setup_triangles and clip_triangles: snap a clip-space
// triangle to the sub-pixel grid, cull back faces of single-sided materials and zero-area
// triangles, append a SetupTriangle and bin it into (triangle, tile) pairs (a large triangle
// leaves that to bin_large_triangles). Needs the Setup, Pairs, Counters and Large buffers and
// the RasterParams push constants of the including kernel.
#ifndef HMB_KERNELS_RASTER_EMIT_TRIANGLE_GLSL
#define HMB_KERNELS_RASTER_EMIT_TRIANGLE_GLSL

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
  // Ordered compares only: a NaN area fails both and is rejected here on every driver, and an
  // infinite one (a vertex at infinity) would leave the bounds below non-finite.
  if (!(abs(area) > 0.0) || isinf(area)) return;
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

#endif
