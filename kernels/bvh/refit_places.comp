#version 450
// Refit's preparation, second: every node's depth (steps up to its root) and its root, so that
// refit_bounds can go up the trees a depth per dispatch and refit_pack find each node's frame.
// The host sorts the nodes by depth from these once per build.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "refit_common.glsl"

REFIT_PARENTS
REFIT_PLACES

void main() {
  const uint node = linearInvocationIndex(HMB_REFIT_GROUP);
  if (node >= params.nodeCount) return;
  uint depth = 0u, up = node;
  for (; up >= params.treeCount; up = parents[up]) ++depth;
  places[node] = uvec2(depth, up);
}
