#version 450
// After build_small_tasks built its subtrees with HMB_SPEC_BVH_PACK_LATER: each node it marked
// (packed x word HMB_BVH_PACK_LATER, y its tree) gets its exact bounds packed in its tree's
// frame, a lane per node; the index word stays. Nodes the levels wrote are packed already.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "bvh_build_common.glsl"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_BVH_PACK_GROUP) in;

void main() {
  const uint node = linearInvocationIndex(HMB_BVH_PACK_GROUP);
  if (node < params.treeCount || node >= counters.nodeCount) return;  // roots: begin_build packs them
  const uvec4 packed = packedNodes[node];
  if (packed.x != HMB_BVH_PACK_LATER) return;
  const BvhNode box = nodes[node];
  packedNodes[node].xyz = packBox(vec3(box.minX, box.minY, box.minZ), vec3(box.maxX, box.maxY, box.maxZ),
                                  frames[packed.y]);
}
