// The closest hit of a ray through the two-level BVH. The top level is walked stackless (each
// node's link for the ray's direction octant says where to go next, kernels/bvh/
// bvh_build_layout.h); each instance's mesh tree depth first with a short stack, which hands
// over to the linked walk for a ray that would need more. Instances of the ignored object are
// skipped whole, so a reveal ray finds the first surface behind the object it starts on.
// Binds the trace scene from the including kernel's HMB_TRACE_SCENE_BINDING on
// (trace_scene_bindings.glsl).
#ifndef HMB_KERNELS_TRACE_CLOSEST_HIT_GLSL
#define HMB_KERNELS_TRACE_CLOSEST_HIT_GLSL

#include "trace_layout.h"
#include "ray_tests.glsl"
#include "../bvh/packed_node.glsl"
#include "trace_scene_bindings.glsl"

// Pending subtrees a ray may keep per mesh tree walk (walkStacked); a specialization constant,
// so tests can force the linked walk that takes over past it.
layout(constant_id = HMB_SPEC_TRACE_STACK) const uint kTraceStackSize = HMB_TRACE_STACK_SIZE;

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

// What both walks through an instance's mesh tree need: the ray in the instance's space, the
// interval's start, the tree's frame, and how back faces are culled.
struct MeshRay {
  PreparedRay r;
  uint instance;
  uint mesh;
  float tMin;
  bool cull;
  float handedness;
  BvhFrame frame;
};

// Tests the leaf's triangles (positions first..first+count-1 of the leaves' order); keeps a hit
// nearer than `best` (ties: lower instance, then lower leaf entry, so that the answer does not
// depend on the visiting order). True when one of them became the closest hit.
bool testLeaf(MeshRay m, uint first, uint count, inout BvhHit best) {
  bool nearest = false;
  for (uint k = 0; k < count; ++k) {
    // The triangles' vertices are stored in the leaves' order: no indirection through the
    // leaf's primitive indices, which name the triangle once, for the closest hit.
    const uint entry = first + k;
    const vec3 p0 = leafTriangles[3u * entry].xyz, p1 = leafTriangles[3u * entry + 1u].xyz,
               p2 = leafTriangles[3u * entry + 2u].xyz;
    float t, u, v;
    if (!intersectTriangle(m.r, p0, p1, p2, t, u, v)) continue;
    if (!(t >= m.tMin) || t > best.t) continue;
    if (m.cull && m.handedness * dot(m.r.direction, cross(p1 - p0, p2 - p0)) > 0.0) continue;
    if (t == best.t && (best.triangle != HMB_NO_HIT) &&
        (m.instance > best.instance || (m.instance == best.instance && entry >= best.entry)))
      continue;
    best.t = t;
    best.u = u;
    best.v = v;
    best.entry = entry;
    best.objectId = traceInstances[m.instance].objectId;
    best.instance = m.instance;
    nearest = true;
  }
  return nearest;
}

// The stackless walk: every node's link for the ray's direction octant says where to go next
// (kernels/bvh/bvh_build_layout.h), so no tree is too deep for it. Each box tested costs a node
// and a link load. True when a hit in this tree became the closest.
bool walkLinked(MeshRay m, inout BvhHit best) {
  bool nearest = false;
  uint node = m.mesh;
  while (node != HMB_BVH_LINK_END) {
    const uvec4 n = meshNodes[node];
    const uint link = meshLinks[node * HMB_BVH_OCTANTS + m.r.octant];
    if (intersectBox(m.r, packedLower(n, m.frame), packedUpper(n, m.frame), m.tMin, best.t)) {
      const uint count = packedCount(n);
      if (count == 0u) {
        node = firstChildOf(n, link);
        continue;
      }
      if (testLeaf(m, packedLeftOrFirst(n), count, best)) nearest = true;
    }
    node = link & HMB_BVH_LINK_NEXT_MASK;
  }
  return nearest;
}

// The subtrees a mesh walk has put off (walkStacked): each one's range word and the distance
// at which the ray enters it. Module scope, so that popPending reads them without a copy.
uint pendingWords[kTraceStackSize];
float pendingEntries[kTraceStackSize];

// The nearest put-off subtree that can still hold a nearer hit (as intersectBox widens): false
// when none is left.
bool popPending(inout uint pending, float bestT, out uint word) {
  word = 0u;
  while (pending > 0u) {
    --pending;
    word = pendingWords[pending];
    if (pendingEntries[pending] <= bestT + abs(bestT) * kBoxSlack) return true;
  }
  return false;
}

// Depth first with a short stack, the nearer child first. A node's two children are adjacent,
// and each packed node carries its own child range, so one step loads both children and tests
// both boxes: two loads per entered node where the linked walk pays two per box tested (on
// lavapipe every load at per-lane addresses is a loop over the lanes). The far child waits on
// the stack with its entry distance, and is dropped when a nearer hit has been found meanwhile.
// Interior steps repeat until the ray holds a leaf, so that the lanes of a SIMD group test
// their leaves together (the while-while form of Aila and Laine). `overflowed` is set, with the
// walk abandoned, when a ray needs more than kTraceStackSize pending subtrees: the caller then
// finishes with the linked walk (best only ever shrinks, so what was found stays right).
bool walkStacked(MeshRay m, inout BvhHit best, out bool overflowed) {
  overflowed = false;
  bool nearest = false;
  uint pending = 0u;
  const uvec4 root = meshNodes[m.mesh];
  float entry;
  if (!intersectBoxEntry(m.r, packedLower(root, m.frame), packedUpper(root, m.frame), m.tMin, best.t, entry))
    return false;
  uint word = root.w;  // the entered node's range: children, or triangles
  for (;;) {
    bool left = true;  // a subtree is left to walk
    while (left && (word & HMB_BVH_PACKED_MAX_COUNT) == 0u) {
      const uint first = word >> HMB_BVH_PACKED_COUNT_BITS;
      const uvec4 a = meshNodes[first], b = meshNodes[first + 1u];
      float entryA, entryB;
      const bool hitA = intersectBoxEntry(m.r, packedLower(a, m.frame), packedUpper(a, m.frame), m.tMin, best.t, entryA);
      const bool hitB = intersectBoxEntry(m.r, packedLower(b, m.frame), packedUpper(b, m.frame), m.tMin, best.t, entryB);
      if (hitA && hitB) {
        if (pending == kTraceStackSize) {
          overflowed = true;
          return nearest;
        }
        const bool aFirst = entryA <= entryB;
        pendingWords[pending] = aFirst ? b.w : a.w;
        pendingEntries[pending] = aFirst ? entryB : entryA;
        ++pending;
        word = aFirst ? a.w : b.w;
      } else if (hitA || hitB) {
        word = hitA ? a.w : b.w;
      } else {
        left = popPending(pending, best.t, word);
      }
    }
    if (!left) return nearest;
    if (testLeaf(m, word >> HMB_BVH_PACKED_COUNT_BITS, word & HMB_BVH_PACKED_MAX_COUNT, best)) nearest = true;
    if (!popPending(pending, best.t, word)) return nearest;
  }
}

// Traces the ray, carried into the instance's space at its shutter time, through the
// instance's mesh tree; keeps a hit that is nearer than `best`.
void traceInstance(uint instance, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  MeshRay m;
  m.instance = instance;
  m.mesh = traceInstances[instance].mesh;
  const uint time = min(ray.time, scene.timeCount - 1u);
  const mat4 objectFromWorld = transforms[instance * scene.timeCount + time].objectFromWorld;
  const vec3 origin = (objectFromWorld * vec4(ray.originTMin.xyz, 1.0)).xyz;
  const vec3 direction = mat3(objectFromWorld) * ray.directionTMax.xyz;
  m.r = prepareRay(origin, direction);
  if (!m.r.valid) return;
  // A back face is one whose counter-clockwise normal the ray runs along; a transform that
  // flips handedness flips that in object space.
  m.cull = (scene.flags & HMB_TRACE_CULL_BACK_FACES) != 0u &&
           (traceInstances[instance].flags & HMB_TRACE_INSTANCE_SINGLE_SIDED) != 0u;
  m.handedness = determinant(mat3(objectFromWorld)) < 0.0 ? -1.0 : 1.0;
  m.tMin = ray.originTMin.w;
  m.frame = meshFrames[m.mesh];
  bool overflowed;
  bool nearestHere = walkStacked(m, best, overflowed);  // best is this instance's: refined below
  if (overflowed && walkLinked(m, best)) nearestHere = true;
  if (nearestHere) {
    best.triangle = meshPrimitives[best.entry];
    const uint at = 3u * best.entry;
    const float refined = planeHitDistance(m.r, leafTriangles[at].xyz, leafTriangles[at + 1u].xyz,
                                           leafTriangles[at + 2u].xyz, best.t);
    best.t = clamp(refined, m.tMin, ray.directionTMax.w);
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
