#version 450
// Closest hit of every ray in a list through the two-level BVH (closest_hit.glsl).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "trace_layout.h"
#define HMB_TRACE_SCENE_BINDING HMB_TRACE_BINDING_SCENE
#include "closest_hit.glsl"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_TRACE_GROUP) in;

layout(std430, binding = HMB_TRACE_BINDING_RAYS) readonly buffer Rays { TraceRay rays[]; };
// Written as two uvec4 per hit: on lavapipe each store at per-lane addresses is a loop over the
// lanes, whatever its width, and a BvhHit stored member by member is eight of them.
layout(std430, binding = HMB_TRACE_BINDING_HITS) writeonly buffer Hits { uvec4 hitWords[]; };
layout(push_constant) uniform Params { TraceParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_TRACE_GROUP);
  if (i >= params.rayCount) return;
  const TraceSceneInfo scene = TraceSceneInfo(params.instanceCount, params.timeCount, params.flags);
  const BvhHit hit = closestHit(rays[i], scene);
  hitWords[2u * i] = uvec4(floatBitsToUint(hit.t), floatBitsToUint(hit.u), floatBitsToUint(hit.v), hit.triangle);
  hitWords[2u * i + 1u] = uvec4(hit.objectId, hit.instance, hit.entry, hit.cut);
}
