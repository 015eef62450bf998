#version 450
// Refit, first: every interior node tells its two children it is their parent (the trees keep
// only the way down).
#extension GL_GOOGLE_include_directive : require
#include "refit_common.glsl"

void main() {
  const uint node = linearInvocationIndex(HMB_REFIT_GROUP);
  if (node >= params.nodeCount || isEmptyRoot(node) || isLeaf(node)) return;
  const uint left = packedLeftOrFirst(packedNodes[node]);
  parents[left] = node;
  parents[left + 1u] = node;
}
