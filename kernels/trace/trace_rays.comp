#version 450
// Closest hit of every ray through the two-level BVH, stackless: each node's link for the
// ray's direction octant says where to go next (kernels/bvh/bvh_build_layout.h), so no
// per-ray stack is kept and no tree is too deep. Instances of the ignored object are skipped
// whole, so a reveal ray finds the first surface behind the object it starts on.
#extension GL_GOOGLE_include_directive : require
#include "trace_layout.h"
#include "ray_tests.glsl"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_TRACE_GROUP) in;

layout(std430, binding = HMB_TRACE_BINDING_RAYS) readonly buffer Rays { TraceRay rays[]; };
layout(std430, binding = HMB_TRACE_BINDING_HITS) writeonly buffer Hits { BvhHit hits[]; };
layout(std430, binding = HMB_TRACE_BINDING_TOP_NODES) readonly buffer TopNodes { BvhNode topNodes[]; };
layout(std430, binding = HMB_TRACE_BINDING_TOP_LINKS) readonly buffer TopLinks { uint topLinks[]; };
layout(std430, binding = HMB_TRACE_BINDING_TOP_PRIMITIVES) readonly buffer TopPrimitives { uint topPrimitives[]; };
layout(std430, binding = HMB_TRACE_BINDING_INSTANCES) readonly buffer Instances { TraceInstance instances[]; };
layout(std430, binding = HMB_TRACE_BINDING_TRANSFORMS) readonly buffer Transforms { InstanceTransform transforms[]; };
layout(std430, binding = HMB_TRACE_BINDING_MESH_NODES) readonly buffer MeshNodes { BvhNode meshNodes[]; };
layout(std430, binding = HMB_TRACE_BINDING_MESH_LINKS) readonly buffer MeshLinks { uint meshLinks[]; };
layout(std430, binding = HMB_TRACE_BINDING_MESH_PRIMITIVES) readonly buffer MeshPrimitives { uint meshPrimitives[]; };
layout(std430, binding = HMB_TRACE_BINDING_TRIANGLES) readonly buffer Triangles { uvec4 triangles[]; };
layout(std430, binding = HMB_TRACE_BINDING_POSITIONS) readonly buffer Positions { vec4 positions[]; };
layout(push_constant) uniform Params { TraceParams params; };

vec3 lowerOf(BvhNode n) { return vec3(n.minX, n.minY, n.minZ); }
vec3 upperOf(BvhNode n) { return vec3(n.maxX, n.maxY, n.maxZ); }

// Where traversal goes after entering interior node n whose link word is `link`.
uint firstChildOf(BvhNode n, uint link) {
  return n.leftOrFirst + ((link & HMB_BVH_LINK_RIGHT_FIRST) != 0u ? 1u : 0u);
}

// Traces the ray, carried into the instance's space at its shutter time, through the
// instance's mesh tree; keeps a hit that is nearer than `best` (ties: lower instance, then
// lower triangle, so the answer does not depend on the visiting order).
void traceInstance(uint instance, TraceRay ray, inout BvhHit best) {
  const TraceInstance inst = instances[instance];
  const uint time = min(ray.time, params.timeCount - 1u);
  const mat4 objectFromWorld = transforms[instance * params.timeCount + time].objectFromWorld;
  const vec3 origin = (objectFromWorld * vec4(ray.originTMin.xyz, 1.0)).xyz;
  const vec3 direction = mat3(objectFromWorld) * ray.directionTMax.xyz;
  const PreparedRay r = prepareRay(origin, direction);
  if (!r.valid) return;
  const float tMin = ray.originTMin.w;
  uint node = inst.mesh;
  while (node != HMB_BVH_LINK_END) {
    const BvhNode n = meshNodes[node];
    const uint link = meshLinks[node * HMB_BVH_OCTANTS + r.octant];
    if (intersectBox(r, lowerOf(n), upperOf(n), tMin, best.t)) {
      if (n.count == 0u) {
        node = firstChildOf(n, link);
        continue;
      }
      for (uint k = 0; k < n.count; ++k) {
        const uint triangle = meshPrimitives[n.leftOrFirst + k];
        const uvec4 tri = triangles[triangle];
        float t, u, v;
        if (!intersectTriangle(r, positions[tri.x].xyz, positions[tri.y].xyz, positions[tri.z].xyz, t, u, v)) continue;
        if (!(t >= tMin) || t > best.t) continue;
        if (t == best.t && (best.triangle != HMB_NO_HIT) &&
            (instance > best.instance || (instance == best.instance && triangle >= best.triangle)))
          continue;
        best.t = t;
        best.u = u;
        best.v = v;
        best.triangle = triangle;
        best.objectId = inst.objectId;
        best.instance = instance;
      }
    }
    node = link & HMB_BVH_LINK_NEXT_MASK;
  }
}

void main() {
  const uint i = linearInvocationIndex(HMB_TRACE_GROUP);
  if (i >= params.rayCount) return;
  const TraceRay ray = rays[i];
  BvhHit best;
  best.t = ray.directionTMax.w;
  best.u = 0.0;
  best.v = 0.0;
  best.triangle = HMB_NO_HIT;
  best.objectId = HMB_NO_HIT;
  best.instance = HMB_NO_HIT;
  best.pad1 = 0u;
  best.pad2 = 0u;
  const PreparedRay r = prepareRay(ray.originTMin.xyz, ray.directionTMax.xyz);
  if (r.valid && params.instanceCount > 0u) {
    uint node = HMB_BVH_ROOT;
    while (node != HMB_BVH_LINK_END) {
      const BvhNode n = topNodes[node];
      const uint link = topLinks[node * HMB_BVH_OCTANTS + r.octant];
      if (intersectBox(r, lowerOf(n), upperOf(n), ray.originTMin.w, best.t)) {
        if (n.count == 0u) {
          node = firstChildOf(n, link);
          continue;
        }
        for (uint k = 0; k < n.count; ++k) {
          const uint instance = topPrimitives[n.leftOrFirst + k];
          if (instances[instance].objectId != ray.ignoreObjectId) traceInstance(instance, ray, best);
        }
      }
      node = link & HMB_BVH_LINK_NEXT_MASK;
    }
  }
  hits[i] = best;
}
