#version 450
// One workgroup per tree: the root's bounds and centroid bounds over its primitive range,
// the identity order of that range, the tree's frame (the root box: its packed bounds count
// steps across it), and the root's task: for level 0, or, for a root of at most kSmallTask
// primitives, for build_small_tasks at once (a small tree, such as a top level over a few
// hundred instances, then costs no level's dispatches). Roots are nodes 0..treeCount-1. A build
// over the host's order (HMB_BVH_BUILD_GIVEN_ORDER) takes its ranges' primitives as they are
// in the array, where others start from the identity.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "bvh_build_common.glsl"
#include "../shared/indexing.glsl"
#include "../shared/ordered_float.glsl"

layout(local_size_x = HMB_BVH_BUILD_GROUP) in;
layout(constant_id = HMB_SPEC_BVH_SMALL_TASK) const uint kSmallTask = HMB_BVH_SMALL_TASK;

shared uint boundsMin[3];
shared uint boundsMax[3];
shared uint centroidMin[3];
shared uint centroidMax[3];

void main() {
  const uint tree = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  if (tree >= params.treeCount) return;  // uniform across the workgroup
  const uint lane = gl_LocalInvocationID.x;
  if (lane < 3) {
    boundsMin[lane] = kOrderedPositiveInfinity;
    boundsMax[lane] = kOrderedNegativeInfinity;
    centroidMin[lane] = kOrderedPositiveInfinity;
    centroidMax[lane] = kOrderedNegativeInfinity;
  }
  barrier();

  const uvec2 range = roots[tree];
  const bool givenOrder = (params.flags & HMB_BVH_BUILD_GIVEN_ORDER) != 0u;
  vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo, cLo = lo, cHi = hi;
  for (uint k = lane; k < range.y; k += HMB_BVH_BUILD_GROUP) {
    uint primitive = range.x + k;
    if (givenOrder) primitive = primitives[primitive];
    else primitives[primitive] = primitive;
    const BvhBox box = boxAt(primitive);
    const vec3 c = centroidOf(box);
    lo = min(lo, box.min.xyz);
    hi = max(hi, box.max.xyz);
    cLo = min(cLo, c);
    cHi = max(cHi, c);
  }
  for (uint a = 0; a < 3; ++a) {
    atomicMin(boundsMin[a], orderedUint(lo[a]));
    atomicMax(boundsMax[a], orderedUint(hi[a]));
    atomicMin(centroidMin[a], orderedUint(cLo[a]));
    atomicMax(centroidMax[a], orderedUint(cHi[a]));
  }
  barrier();

  if (lane != 0) return;
  BvhNode root;
  root.minX = orderedFloat(boundsMin[0]);
  root.minY = orderedFloat(boundsMin[1]);
  root.minZ = orderedFloat(boundsMin[2]);
  root.maxX = orderedFloat(boundsMax[0]);
  root.maxY = orderedFloat(boundsMax[1]);
  root.maxZ = orderedFloat(boundsMax[2]);
  // A lone primitive is a leaf now; an empty tree an empty leaf-less root that no ray enters;
  // a root with children gets their index from its task.
  root.leftOrFirst = range.x;
  root.count = range.y == 1u ? 1u : 0u;
  nodes[tree] = root;
  const vec3 rootLo = vec3(root.minX, root.minY, root.minZ), rootHi = vec3(root.maxX, root.maxY, root.maxZ);
  const BvhFrame frame = frameOf(rootLo, rootHi);
  frames[tree] = frame;
  // A root with children gets its index word from its task.
  packedNodes[tree] = uvec4(packBox(rootLo, rootHi, frame), packLeftOrFirstCount(range.x, root.count));
  if (range.y <= 1u) {
    if (range.y == 1u) atomicAdd(counters.leafCount, 1u);
    return;
  }
  BvhBuildTask task;
  task.node = tree;
  task.first = range.x;
  task.count = range.y;
  task.tree = tree;
  task.centroidMin = vec4(orderedFloat(centroidMin[0]), orderedFloat(centroidMin[1]), orderedFloat(centroidMin[2]), 0.0);
  task.centroidMax = vec4(orderedFloat(centroidMax[0]), orderedFloat(centroidMax[1]), orderedFloat(centroidMax[2]), 0.0);
  if (range.y <= kSmallTask) {
    // Level 0, its range in the primitive array's first half, where this kernel wrote it.
    task.centroidMin.w = 0.0;
    task.centroidMax.w = 0.0;
    tasks[2u * params.taskCapacity + atomicAdd(counters.smallTaskCount, 1u)] = task;
    return;
  }
  tasks[atomicAdd(counters.taskCount[0], 1u)] = task;
}
