#version 450
// Refit, last: every refitted node's new exact box packed in its tree's new frame (the root's
// new box), which the root's invocation also stores. The index words stay.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "refit_common.glsl"

REFIT_ROOTS
REFIT_PACKED_NODES
REFIT_FRAMES
REFIT_EXACT
REFIT_PLACES
REFIT_ORDER

void main() {
  const uint i = linearInvocationIndex(HMB_REFIT_GROUP);
  if (i >= params.count) return;
  const uint node = order[params.first + i];
  if (IS_EMPTY_ROOT(node)) return;
  const uint tree = places[node].y;
  const BvhBox root = exact[tree];
  const BvhFrame frame = frameOf(root.min.xyz, root.max.xyz);
  if (node == tree) frames[tree] = frame;
  const BvhBox box = exact[node];
  packedNodes[node].xyz = packBox(box.min.xyz, box.max.xyz, frame);
}
