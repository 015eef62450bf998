// The closest hit of a ray through the two-level BVH: the top level over instances, then each
// instance's mesh tree, both walked depth first with a short stack. A ray that would need more
// hands over to the linked walk, stackless: each node's link for the ray's direction octant
// says where to go next (kernels/bvh/bvh_build_layout.h). Instances of the ignored object are
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
  uint objectId;  // the instance's, for its hits
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
    const vec3 p0 = leafTriangle(3u * entry).xyz, p1 = leafTriangle(3u * entry + 1u).xyz,
               p2 = leafTriangle(3u * entry + 2u).xyz;
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
    best.objectId = m.objectId;
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
    const uvec4 n = meshNode(node);
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

// The subtrees a walk has put off: each one's range word and the distance at which the ray
// enters it, one stack for the top-level walk and one for the mesh walk it runs per instance.
// Module scope, so that the steps below read them without a copy.
#define TOP_WALK 0
#define MESH_WALK 1
uint pendingWords[2][kTraceStackSize];
float pendingEntries[2][kTraceStackSize];

// The nearest put-off subtree that can still hold a nearer hit (as intersectBox widens): false
// when none is left.
bool popPending(uint walk, inout uint pending, float bestT, out uint word) {
  word = 0u;
  while (pending > 0u) {
    --pending;
    word = pendingWords[walk][pending];
    if (pendingEntries[walk][pending] <= bestT + abs(bestT) * kBoxSlack) return true;
  }
  return false;
}

// One interior step of a stacked walk: the entered node's children a and b (loaded by the
// caller from its tree) tested, the nearer one hit entered and the farther put off, or the
// nearest put-off subtree taken up when neither is hit. Returns false when nothing is left to
// walk; sets `overflowed` (and returns false) when a subtree cannot be put off.
bool interiorStep(uint walk, uvec4 a, uvec4 b, PreparedRay r, BvhFrame frame, float tMin, float bestT,
                  inout uint pending, inout uint word, inout bool overflowed) {
  float entryA, entryB;
  const bool hitA = intersectBoxEntry(r, packedLower(a, frame), packedUpper(a, frame), tMin, bestT, entryA);
  const bool hitB = intersectBoxEntry(r, packedLower(b, frame), packedUpper(b, frame), tMin, bestT, entryB);
  if (hitA && hitB) {
    if (pending == kTraceStackSize) {
      overflowed = true;
      return false;
    }
    const bool aFirst = entryA <= entryB;
    pendingWords[walk][pending] = aFirst ? b.w : a.w;
    pendingEntries[walk][pending] = aFirst ? entryB : entryA;
    ++pending;
    word = aFirst ? a.w : b.w;
    return true;
  }
  if (hitA || hitB) {
    word = hitA ? a.w : b.w;
    return true;
  }
  return popPending(walk, pending, bestT, word);
}

bool isInterior(uint word) { return (word & HMB_BVH_PACKED_MAX_COUNT) == 0u; }

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
  const uvec4 root = meshNode(m.mesh);
  float entry;
  if (!intersectBoxEntry(m.r, packedLower(root, m.frame), packedUpper(root, m.frame), m.tMin, best.t, entry))
    return false;
  uint word = root.w;  // the entered node's range: children, or triangles
  for (;;) {
    bool left = true;  // a subtree is left to walk
    while (left && isInterior(word)) {
      const uint first = word >> HMB_BVH_PACKED_COUNT_BITS;
      left = interiorStep(MESH_WALK, meshNode(first), meshNode(first + 1u), m.r, m.frame, m.tMin, best.t, pending,
                          word, overflowed);
    }
    if (!left) return nearest;
    if (testLeaf(m, word >> HMB_BVH_PACKED_COUNT_BITS, word & HMB_BVH_PACKED_MAX_COUNT, best)) nearest = true;
    if (!popPending(MESH_WALK, pending, best.t, word)) return nearest;
  }
}

// The ray carried into the instance's space at its shutter time.
PreparedRay instanceRay(uint instance, TraceRay ray, TraceSceneInfo scene, out mat3 linear) {
  const uint time = min(ray.time, scene.timeCount - 1u);
  const mat4 objectFromWorld = objectFromWorldAt(instance * scene.timeCount + time);
  linear = mat3(objectFromWorld);
  return prepareRay((objectFromWorld * vec4(ray.originTMin.xyz, 1.0)).xyz, linear * ray.directionTMax.xyz);
}

// Traces the ray, carried into the instance's space at its shutter time, through the
// instance's mesh tree; keeps a hit that is nearer than `best`. Every hit is compared at the
// watertight test's distance, whichever instance it is in, so the closest hit does not depend
// on the order instances are visited in; closestHit refines the winner's distance once.
void traceInstance(uint instance, TraceInstance record, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  MeshRay m;
  m.instance = instance;
  m.objectId = record.objectId;
  m.mesh = record.mesh;
  mat3 linear;
  m.r = instanceRay(instance, ray, scene, linear);
  if (!m.r.valid) return;
  // A back face is one whose counter-clockwise normal the ray runs along; a transform that
  // flips handedness flips that in object space.
  m.cull = (scene.flags & HMB_TRACE_CULL_BACK_FACES) != 0u &&
           (record.flags & HMB_TRACE_INSTANCE_SINGLE_SIDED) != 0u;
  m.handedness = determinant(linear) < 0.0 ? -1.0 : 1.0;
  m.tMin = ray.originTMin.w;
  m.frame = meshFrameAt(m.mesh);
  bool overflowed;
  bool nearestHere = walkStacked(m, best, overflowed);
  if (overflowed && walkLinked(m, best)) nearestHere = true;
  if (nearestHere) best.triangle = meshPrimitives[best.entry];
}

// The closest hit's distance from its triangle's plane (planeHitDistance), in its instance's
// space, within [tMin, tMax].
void refineClosestHit(TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  if (best.triangle == HMB_NO_HIT) return;
  mat3 linear;
  const PreparedRay r = instanceRay(best.instance, ray, scene, linear);
  const uint at = 3u * best.entry;
  const float refined =
      planeHitDistance(r, leafTriangle(at).xyz, leafTriangle(at + 1u).xyz, leafTriangle(at + 2u).xyz, best.t);
  best.t = clamp(refined, ray.originTMin.w, ray.directionTMax.w);
}

// The instances of a top-level leaf (first..first+count-1 of its primitive order), each traced
// unless it is the ignored object.
void traceTopLeaf(uint first, uint count, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  for (uint k = 0; k < count; ++k) {
    const uint instance = topPrimitives[first + k];
    const TraceInstance record = traceInstanceAt(instance);  // read once for all it gives
    if (record.objectId != ray.ignoreObjectId) traceInstance(instance, record, ray, scene, best);
  }
}

// The top level walked as walkStacked walks a mesh tree; false when it overflowed its stack.
bool walkTopStacked(PreparedRay r, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  bool overflowed = false;
  uint pending = 0u;
  const BvhFrame frame = topFrame;
  const float tMin = ray.originTMin.w;
  const uvec4 root = topNode(HMB_BVH_ROOT);
  float entry;
  if (!intersectBoxEntry(r, packedLower(root, frame), packedUpper(root, frame), tMin, best.t, entry)) return true;
  uint word = root.w;
  for (;;) {
    bool left = true;
    while (left && isInterior(word)) {
      const uint first = word >> HMB_BVH_PACKED_COUNT_BITS;
      left = interiorStep(TOP_WALK, topNode(first), topNode(first + 1u), r, frame, tMin, best.t, pending, word,
                          overflowed);
    }
    if (!left) return !overflowed;
    traceTopLeaf(word >> HMB_BVH_PACKED_COUNT_BITS, word & HMB_BVH_PACKED_MAX_COUNT, ray, scene, best);
    if (!popPending(TOP_WALK, pending, best.t, word)) return true;
  }
}

// The top level's linked walk, for a ray that overflowed the stacked one: from the root again,
// with what was found so far.
void walkTopLinked(PreparedRay r, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  const BvhFrame frame = topFrame;
  uint node = HMB_BVH_ROOT;
  while (node != HMB_BVH_LINK_END) {
    const uvec4 n = topNode(node);
    const uint link = topLinks[node * HMB_BVH_OCTANTS + r.octant];
    if (intersectBox(r, packedLower(n, frame), packedUpper(n, frame), ray.originTMin.w, best.t)) {
      const uint count = packedCount(n);
      if (count == 0u) {
        node = firstChildOf(n, link);
        continue;
      }
      traceTopLeaf(packedLeftOrFirst(n), count, ray, scene, best);
    }
    node = link & HMB_BVH_LINK_NEXT_MASK;
  }
}

// The closest hit in [tMin, tMax] of the ray; a miss has triangle == HMB_NO_HIT and t == tMax.
BvhHit closestHit(TraceRay ray, TraceSceneInfo scene) {
  BvhHit best = missedHit(ray.directionTMax.w);
  const PreparedRay r = prepareRay(ray.originTMin.xyz, ray.directionTMax.xyz);
  if (!r.valid || scene.instanceCount == 0u) return best;
  if (!walkTopStacked(r, ray, scene, best)) walkTopLinked(r, ray, scene, best);
  refineClosestHit(ray, scene, best);
  return best;
}

#endif
