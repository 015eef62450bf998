#version 450
// Per scene triangle: trivial frustum reject, then the common case, a triangle inside the near
// plane and the guard band, is snapped, culled and binned here (emit_triangle.glsl). The rest
// is listed for clip_triangles: kernels that clip hold polygons in arrays, and on CPU devices a
// kernel with such arrays pays for them in every invocation, needed or not.
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

void main() {
  const uint t = linearInvocationIndex(HMB_RASTER_GROUP);
  if (t >= params.triangleCount) return;
  const GpuTriangle tri = triangles[t];
  const vec4 a = clipCurrent[tri.v0], b = clipCurrent[tri.v1], c = clipCurrent[tri.v2];
  if (any(isnan(a)) || any(isinf(a)) || any(isnan(b)) || any(isinf(b)) || any(isnan(c)) || any(isinf(c))) return;

  // Trivial reject: all three vertices outside one frustum plane (x, y within w; z within [0, w]).
  if ((a.x > a.w && b.x > b.w && c.x > c.w) || (a.x < -a.w && b.x < -b.w && c.x < -c.w) ||
      (a.y > a.w && b.y > b.w && c.y > c.w) || (a.y < -a.w && b.y < -b.w && c.y < -c.w) ||
      (a.z < 0.0 && b.z < 0.0 && c.z < 0.0) || (a.z > a.w && b.z > b.w && c.z > c.w))
    return;

  if (insideClipVolume(a) && insideClipVolume(b) && insideClipVolume(c)) {
    const bool doubleSided = (instances[tri.instance].flags & HMB_INSTANCE_DOUBLE_SIDED) != 0u;
    emitTriangle(a, b, c, t, doubleSided);
  } else {
    const uint slot = atomicAdd(counters.clipCount, 1u);
    if (slot < params.clipCapacity) clipList[slot] = t;
    else atomicOr(counters.overflow, HMB_RASTER_OVERFLOW_CLIP);
  }
}
