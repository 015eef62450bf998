// The closest hit of a ray through the two-level BVH: the top level over instances, then each
// instance's mesh tree, both walked depth first with a stack of pending subtrees, one per level
// at most: the builder bounds every tree's depth (HMB_BVH_MAX_DEPTH), so no walk needs a
// stackless fallback. (One was here: on lavapipe, which runs both sides of every branch under
// a mask, its code cost 10-15% of the trace rate though no ray took it.) Instances of the
// ignored object are skipped whole, so a reveal ray finds the first surface behind the object
// it starts on.
// Mesa 22.3's lavapipe ends every loop of an invocation, silently, once its rounds reach 65535
// in all (a ray through 20,000 instances' boxes, or a kernel's many traces): each loop here
// checks, as it leaves, whether it left before its end, and a cut trace is flagged
// (BvhHit::cut) and counted in the trace status, so that the host can say so.
// Binds the trace scene from the including kernel's HMB_TRACE_SCENE_BINDING on
// (trace_scene_bindings.glsl).
#ifndef HMB_KERNELS_TRACE_CLOSEST_HIT_GLSL
#define HMB_KERNELS_TRACE_CLOSEST_HIT_GLSL

#include "trace_layout.h"
#include "ray_tests.glsl"
#include "../bvh/packed_node.glsl"
#include "trace_scene_bindings.glsl"

// False builds the kernel for a scene of exactly one instance (the host chooses:
// GpuScene::topLevelWalk, passes::TraceRaysPass): rays enter that instance's tree directly.
// On lavapipe (Mesa 22.3), which runs the code of every branch and at least one round of every
// loop under the lanes' mask, walking a top level whose root is that one instance's leaf cost a
// tenth of a coherent trace: node reads, a push and a pop for no lane.
layout(constant_id = HMB_SPEC_TRACE_TOP_LEVEL) const bool kTopLevelWalk = true;

// What a trace needs to know of the scene beside its buffers.
struct TraceSceneInfo {
  uint instanceCount;
  uint timeCount;  // transforms per instance
  uint flags;      // HMB_TRACE_*
};

BvhHit missedHit(float tMax) {
  BvhHit hit;
  hit.t = tMax;
  hit.u = 0.0;
  hit.v = 0.0;
  hit.triangle = HMB_NO_HIT;
  hit.objectId = HMB_NO_HIT;
  hit.instance = HMB_NO_HIT;
  hit.entry = HMB_NO_HIT;
  hit.cut = 0u;
  return hit;
}

// Set when a loop of the current trace left before its end (see the top).
bool walkCut = false;
void noteCut(bool cut) { walkCut = walkCut || cut; }

// A ray against one tree's packed boxes, in the tree's steps: the plane q steps from the
// frame's origin is met at t = q a + c on its axis (a = step / d, c = (origin - o) / d), one
// fused multiply-add where decoding the bound and intersecting it took four operations. That t
// differs from the one through the stored float bound by the roundings of a, c and the fma and
// by the bound's own rounding (origin + q step), together under 8 ulps of
// q_max |a| + |c| + |origin / d|: the entry planes are moved nearer and the exit planes farther
// by that much (cEntry, cExit), so every box the exact test meets is met. On an axis the ray
// runs across (a zero direction component) q a + c is inf - inf, a NaN the test leaves out, and
// such a ray walked every box its other axes met (a ray along x beside 10,000 boxes in a row
// visited 75,000 nodes): there the plane q is met at (q - s) K for the origin's place s in steps
// and a large K, by its sign, widened a step each way, so a box is met exactly when the ray's
// line lies within a step of its slab.
struct TreeRay {
  vec3 a;
  vec3 cEntry;
  vec3 cExit;
  bvec3 negative;
};

TreeRay treeRay(PreparedRay r, BvhFrame frame) {
  TreeRay t;
  t.a = frame.step.xyz * r.inverseDirection;
  const vec3 c = (frame.origin.xyz - r.origin) * r.inverseDirection;
  const vec3 slack = (abs(t.a) * float(HMB_BVH_QUANTUM_MAX) + abs(c) + abs(frame.origin.xyz * r.inverseDirection)) *
                     (8.0 / 16777216.0);
  t.cEntry = c - slack;
  t.cExit = c + slack;
  t.negative = r.negative;
  const bvec3 across = isinf(r.inverseDirection);
  if (any(across)) {
    const float K = 1e30;  // 65537 K stays finite
    const vec3 offset = r.origin - frame.origin.xyz;
    // A flat frame axis (step 0) has every bound at its origin: the ray's place is below or
    // above every q, or 0 on it.
    const vec3 outside = mix(vec3(-2.0), vec3(float(HMB_BVH_QUANTUM_MAX) + 2.0), greaterThan(offset, vec3(0.0)));
    const vec3 s = mix(offset / frame.step.xyz, outside, equal(frame.step.xyz, vec3(0.0)));
    const vec3 place = mix(s, vec3(0.0), equal(offset, vec3(0.0)));
    const vec3 a = mix(vec3(K), vec3(-K), r.negative);
    t.a = mix(t.a, a, across);
    t.cEntry = mix(t.cEntry, -place * a - K, across);
    t.cExit = mix(t.cExit, -place * a + K, across);
  }
  return t;
}

// intersectBoxEntry for a packed node of the tree, through its TreeRay.
bool intersectPackedBox(TreeRay t, uvec4 node, float tMin, float tMax, out float near) {
  const uvec3 lower = node.xyz & 0xffffu, upper = node.xyz >> 16u;
  const vec3 entry = fma(vec3(mix(lower, upper, t.negative)), t.a, t.cEntry);
  const vec3 exit = fma(vec3(mix(upper, lower, t.negative)), t.a, t.cExit);
  return slabsMeet(entry, exit, tMin, tMax, near);
}

// What the walk through an instance's mesh tree needs: the ray in the instance's space, the
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
  uint k = 0u;
  do {  // a leaf holds at least one triangle (the loops' tests come last: see walkMesh)
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
  } while (++k < count);
  noteCut(k < count);
  return nearest;
}

// The subtrees a walk has put off: each one's range word and the distance at which the ray
// enters it, one stack for the top-level walk and one for the mesh walk it runs per instance.
// Module scope, so that the steps below read them without a copy.
#define TOP_WALK 0
#define MESH_WALK 1
uint pendingWords[2][HMB_TRACE_STACK_SIZE];
float pendingEntries[2][HMB_TRACE_STACK_SIZE];

// The nearest put-off subtree that can still hold a nearer hit (as intersectBox widens): false
// when none is left.
bool popPending(uint walk, inout uint pending, float bestT, out uint word) {
  word = 0u;
  while (pending > 0u) {
    --pending;
    word = pendingWords[walk][pending];
    if (pendingEntries[walk][pending] <= bestT + abs(bestT) * kBoxSlack) return true;
  }
  noteCut(pending > 0u);
  return false;
}

// One interior step of a stacked walk: the entered node's children a and b (loaded by the
// caller from its tree) tested, the nearer one hit entered and the farther put off, or the
// nearest put-off subtree taken up when neither is hit. Returns false when nothing is left to
// walk. A walk at depth d holds at most d pending subtrees, and no node is deeper than the
// stack is long (HMB_TRACE_STACK_SIZE); the index is clamped all the same, so that a tree
// that broke the bound could only cost hits, never write past the stack.
bool interiorStep(uint walk, uvec4 a, uvec4 b, TreeRay tree, float tMin, float bestT, inout uint pending,
                  inout uint word) {
  float entryA, entryB;
  const bool hitA = intersectPackedBox(tree, a, tMin, bestT, entryA);
  const bool hitB = intersectPackedBox(tree, b, tMin, bestT, entryB);
  if (hitA && hitB) {
    const bool aFirst = entryA <= entryB;
    const uint slot = min(pending, HMB_TRACE_STACK_SIZE - 1u);
    pendingWords[walk][slot] = aFirst ? b.w : a.w;
    pendingEntries[walk][slot] = aFirst ? entryB : entryA;
    pending = slot + 1u;
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

// Depth first, the nearer child first. A node's two children are adjacent, and each packed node
// carries its own child range, so one step loads both children and tests both boxes: two loads
// per entered node (on lavapipe each texel fetch is a gather per word). The far child waits on
// the stack with its entry distance, and is dropped when a nearer hit has been found meanwhile.
// Interior steps repeat until the ray holds a leaf, so that the lanes of a SIMD group test
// their leaves together (the while-while form of Aila and Laine). True when a hit in this tree
// became the closest.
// Loops that run at least once test at their end: lavapipe (Mesa 22.3) runs every branch's
// code under the lanes' mask, and a loop whose test comes first one more round for no lane
// (a whole interior step after each descent, a triangle test after each leaf).
bool walkMesh(MeshRay m, inout BvhHit best) {
  bool nearest = false;
  uint pending = 0u;
  const uvec4 root = meshNode(m.mesh);
  const TreeRay tree = treeRay(m.r, m.frame);
  float entry;
  if (!intersectPackedBox(tree, root, m.tMin, best.t, entry)) return false;
  uint word = root.w;  // the entered node's range: children, or triangles
  // Ends by a return; the count only lets a cut show (a loop the driver ends falls through).
  for (uint round = 0u; round != 0xFFFFFFFFu; ++round) {
    bool left = true;  // a subtree is left to walk
    if (isInterior(word)) {
      do {
        const uint first = word >> HMB_BVH_PACKED_COUNT_BITS;
        left = interiorStep(MESH_WALK, meshNode(first), meshNode(first + 1u), tree, m.tMin, best.t, pending, word);
      } while (left && isInterior(word));
      noteCut(left && isInterior(word));
    }
    if (!left || walkCut) return nearest;
    if (testLeaf(m, word >> HMB_BVH_PACKED_COUNT_BITS, word & HMB_BVH_PACKED_MAX_COUNT, best)) nearest = true;
    if (!popPending(MESH_WALK, pending, best.t, word)) return nearest;
  }
  noteCut(true);
  return nearest;
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
  if (walkMesh(m, best)) best.triangle = meshPrimitives[best.entry];
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

// The instance traced unless it is the ignored object.
void traceUnlessIgnored(uint instance, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  const TraceInstance record = traceInstanceAt(instance);  // read once for all it gives
  if (record.objectId != ray.ignoreObjectId) traceInstance(instance, record, ray, scene, best);
}

// The instances of a top-level leaf (first..first+count-1 of its primitive order).
void traceTopLeaf(uint first, uint count, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  uint k = 0u;
  do {  // a leaf holds at least one instance
    traceUnlessIgnored(topPrimitives[first + k], ray, scene, best);
  } while (++k < count);
  noteCut(k < count);
}

// The top level walked as walkMesh walks a mesh tree.
void walkTop(PreparedRay r, TraceRay ray, TraceSceneInfo scene, inout BvhHit best) {
  uint pending = 0u;
  const BvhFrame frame = topFrame;
  const float tMin = ray.originTMin.w;
  const uvec4 root = topNode(HMB_BVH_ROOT);
  const TreeRay tree = treeRay(r, frame);
  float entry;
  if (!intersectPackedBox(tree, root, tMin, best.t, entry)) return;
  uint word = root.w;
  for (uint round = 0u; round != 0xFFFFFFFFu; ++round) {  // as walkMesh's
    bool left = true;
    if (isInterior(word)) {
      do {
        const uint first = word >> HMB_BVH_PACKED_COUNT_BITS;
        left = interiorStep(TOP_WALK, topNode(first), topNode(first + 1u), tree, tMin, best.t, pending, word);
      } while (left && isInterior(word));
      noteCut(left && isInterior(word));
    }
    if (!left || walkCut) return;
    traceTopLeaf(word >> HMB_BVH_PACKED_COUNT_BITS, word & HMB_BVH_PACKED_MAX_COUNT, ray, scene, best);
    if (!popPending(TOP_WALK, pending, best.t, word)) return;
  }
  noteCut(true);
}

// The closest hit in [tMin, tMax] of the ray; a miss has triangle == HMB_NO_HIT and t == tMax.
// A walk cut short (see the top) keeps what it found, flagged and counted.
BvhHit closestHit(TraceRay ray, TraceSceneInfo scene) {
  BvhHit best = missedHit(ray.directionTMax.w);
  const PreparedRay r = prepareRay(ray.originTMin.xyz, ray.directionTMax.xyz);
  if (!r.valid || scene.instanceCount == 0u) return best;
  walkCut = false;
  if (kTopLevelWalk)
    walkTop(r, ray, scene, best);
  else
    traceUnlessIgnored(0u, ray, scene, best);  // the scene's one instance
  refineClosestHit(ray, scene, best);
  if (walkCut) {
    best.cut = 1u;
    atomicAdd(traceStatus[HMB_TRACE_STATUS_CUT_TRACES], 1u);
  }
  return best;
}

#endif
