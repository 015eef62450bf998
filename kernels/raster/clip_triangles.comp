#version 450
// The triangles setup_triangles listed as crossing the near plane or the guard band:
// Sutherland-Hodgman against each plane, then a fan of up to six triangles, each snapped,
// culled and binned like the unclipped ones (emit_triangle.glsl). Same bindings as setup.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
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
layout(std430, binding = HMB_SETUP_BINDING_CLIP_LIST) buffer ClipList { uint clipList[]; };
layout(push_constant) uniform Params { RasterParams params; };

#include "clip_planes.h"
#include "emit_triangle.glsl"

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

void clipAndEmit(vec4 a, vec4 b, vec4 c, uint t, bool doubleSided) {
  vec4 polygon[kMaxPolygon];
  polygon[0] = a;
  polygon[1] = b;
  polygon[2] = c;
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

void main() {
  const uint i = linearInvocationIndex(HMB_RASTER_GROUP);
  if (i >= min(counters.clipCount, params.clipCapacity)) return;
  const uint t = clipList[i];
  const GpuTriangle tri = triangles[t];
  const bool doubleSided = (instances[tri.instance].flags & HMB_INSTANCE_DOUBLE_SIDED) != 0u;
  clipAndEmit(clipCurrent[tri.v0], clipCurrent[tri.v1], clipCurrent[tri.v2], t, doubleSided);
}
