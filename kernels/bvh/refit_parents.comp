#version 450
// Refit's preparation, first: every interior node tells its two children it is their parent
// (the trees keep only the way down).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "refit_common.glsl"

REFIT_ROOTS
REFIT_PACKED_NODES
REFIT_PARENTS

void main() {
  const uint node = linearInvocationIndex(HMB_REFIT_GROUP);
  if (node >= params.nodeCount || IS_EMPTY_ROOT(node) || packedCount(packedNodes[node]) != 0u) return;
  const uint left = packedLeftOrFirst(packedNodes[node]);
  parents[left] = node;
  parents[left + 1u] = node;
}
