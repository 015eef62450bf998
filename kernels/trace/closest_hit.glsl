// The closest hit of a ray through the two-level BVH, stackless: each node's link for the
// ray's direction octant says where to go next (kernels/bvh/bvh_build_layout.h), so no
// per-ray stack is kept and no tree is too deep. Instances of the ignored object are skipped
// whole, so a reveal ray finds the first surface behind the object it starts on.
// Binds the trace scene from the including kernel's HMB_TRACE_SCENE_BINDING on
// (trace_scene_bindings.glsl).
#ifndef HMB_KERNELS_TRACE_CLOSEST_HIT_GLSL
#define HMB_KERNELS_TRACE_CLOSEST_HIT_GLSL

#include "trace_layout.h"
#include "ray_tests.glsl"
#include "../bvh/packed_node.glsl"
#include "trace_scene_bindings.glsl"

// What a trace needs to know of the scene beside its buffers.
struct TraceSceneInfo {
  uint instanceCount;
  uint timeCount;  // transforms per instance
  uint flags;      // HMB_TRACE_*
};

// Where traversal goes after entering interior node n whose link word is `link`.
uint firstChildOf(uvec4 n, uint link) {
  return packedLeftOrFirst(n) + ((link & HMB_BVH_LINK_RIGHT_FIRST) != 0u ? 1u : 0u);
}

BvhHit missedHit(float tMax) {
  BvhHit hit;
  hit.t = tMax;
  hit.u = 0.0;
  hit.v = 0.0;
  hit.triangle = HMB_NO_HIT;
  hit.objectId = HMB_NO_HIT;
  hit.instance = HMB_NO_HIT;
  hit.entry = HMB_NO_HIT;
  hit.pad2 = 0u;
  return hit;
}

// Traces the ray, carried into the instance's space at its shutter time, through the
// instance's mesh tree; keeps a hit that is nearer than `best` (ties: lower instance, then
// lower leaf entry, so the answer does not depend on the visiting order).
void traceInstance(uint instance, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  const uint mesh = traceInstances[instance].mesh;
  const uint time = min(ray.time, scene.timeCount - 1u);
  const mat4 objectFromWorld = transforms[instance * scene.timeCount + time].objectFromWorld;
  const vec3 origin = (objectFromWorld * vec4(ray.originTMin.xyz, 1.0)).xyz;
  const vec3 direction = mat3(objectFromWorld) * ray.directionTMax.xyz;
  const PreparedRay r = prepareRay(origin, direction);
  if (!r.valid) return;
  // A back face is one whose counter-clockwise normal the ray runs along; a transform that
  // flips handedness flips that in object space.
  const bool cull = (scene.flags & HMB_TRACE_CULL_BACK_FACES) != 0u &&
                    (traceInstances[instance].flags & HMB_TRACE_INSTANCE_SINGLE_SIDED) != 0u;
  const float handedness = determinant(mat3(objectFromWorld)) < 0.0 ? -1.0 : 1.0;
  const float tMin = ray.originTMin.w;
  const BvhFrame frame = meshFrames[mesh];
  bool nearestHere = false;  // best is this instance's: its distance is refined at the end
  uint node = mesh;
  while (node != HMB_BVH_LINK_END) {
    const uvec4 n = meshNodes[node];
    const uint link = meshLinks[node * HMB_BVH_OCTANTS + r.octant];
    if (intersectBox(r, packedLower(n, frame), packedUpper(n, frame), tMin, best.t)) {
      const uint count = packedCount(n);
      if (count == 0u) {
        node = firstChildOf(n, link);
        continue;
      }
      const uint first = packedLeftOrFirst(n);
      for (uint k = 0; k < count; ++k) {
        // The triangles are stored in the leaves' order: no indirection through the leaf's
        // primitive indices, which name the triangle once, for the closest hit.
        const uint entry = first + k;
        const uvec4 tri = traceTriangles[entry];
        const vec3 p0 = positions[tri.x].xyz, p1 = positions[tri.y].xyz, p2 = positions[tri.z].xyz;
        float t, u, v;
        if (!intersectTriangle(r, p0, p1, p2, t, u, v)) continue;
        if (!(t >= tMin) || t > best.t) continue;
        if (cull && handedness * dot(direction, cross(p1 - p0, p2 - p0)) > 0.0) continue;
        if (t == best.t && (best.triangle != HMB_NO_HIT) &&
            (instance > best.instance || (instance == best.instance && entry >= best.entry)))
          continue;
        best.t = t;
        best.u = u;
        best.v = v;
        best.entry = entry;
        best.objectId = traceInstances[instance].objectId;
        best.instance = instance;
        nearestHere = true;
      }
    }
    node = link & HMB_BVH_LINK_NEXT_MASK;
  }
  if (nearestHere) {
    best.triangle = meshPrimitives[best.entry];
    const uvec4 tri = traceTriangles[best.entry];
    const float refined = planeHitDistance(r, positions[tri.x].xyz, positions[tri.y].xyz, positions[tri.z].xyz, best.t);
    best.t = clamp(refined, tMin, ray.directionTMax.w);
  }
}

// The closest hit in [tMin, tMax] of the ray; a miss has triangle == HMB_NO_HIT and t == tMax.
BvhHit closestHit(TraceRay ray, TraceSceneInfo scene) {
  BvhHit best = missedHit(ray.directionTMax.w);
  const PreparedRay r = prepareRay(ray.originTMin.xyz, ray.directionTMax.xyz);
  if (!r.valid || scene.instanceCount == 0u) return best;
  const BvhFrame frame = topFrame;
  uint node = HMB_BVH_ROOT;
  while (node != HMB_BVH_LINK_END) {
    const uvec4 n = topNodes[node];
    const uint link = topLinks[node * HMB_BVH_OCTANTS + r.octant];
    if (intersectBox(r, packedLower(n, frame), packedUpper(n, frame), ray.originTMin.w, best.t)) {
      const uint count = packedCount(n);
      if (count == 0u) {
        node = firstChildOf(n, link);
        continue;
      }
      const uint first = packedLeftOrFirst(n);
      for (uint k = 0; k < count; ++k) {
        const uint instance = topPrimitives[first + k];
        if (traceInstances[instance].objectId != ray.ignoreObjectId) traceInstance(instance, ray, scene, best);
      }
    }
    node = link & HMB_BVH_LINK_NEXT_MASK;
  }
  return best;
}

#endif
