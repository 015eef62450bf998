#version 450
// Refit, second: every node's depth (steps up to its root), so that refit_bounds can go up the
// trees a depth per dispatch.
#extension GL_GOOGLE_include_directive : require
#include "refit_common.glsl"

void main() {
  const uint node = linearInvocationIndex(HMB_REFIT_GROUP);
  if (node >= params.nodeCount) return;
  uint depth = 0u;
  for (uint up = node; up >= params.treeCount; up = parents[up]) ++depth;
  depths[node] = depth;
}
