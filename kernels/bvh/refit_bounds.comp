#version 450
// Refit, first, once per depth from the deepest up, over that depth's nodes alone (the order
// the host sorted by depth): each gets its new exact box, a leaf over its primitives' new
// boxes, an interior node over its children's (bounded by the dispatch before). A dispatch per
// depth orders the writes without relying on memory ordering between invocations of one
// dispatch (a climb from each leaf with a per-node arrival count needs it, and lost arrivals
// on lavapipe with memoryBarrierBuffer in its loop).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "refit_common.glsl"

REFIT_BOXES
REFIT_ROOTS
REFIT_PRIMITIVES
REFIT_PACKED_NODES
REFIT_EXACT
REFIT_ORDER

void main() {
  const uint i = linearInvocationIndex(HMB_REFIT_GROUP);
  if (i >= params.count) return;
  const uint node = order[params.first + i];
  if (IS_EMPTY_ROOT(node)) return;
  const uvec4 packed = packedNodes[node];
  vec3 lo = vec3(uintBitsToFloat(0x7f800000u)), hi = -lo;
  if (packedCount(packed) == 0u) {
    const uint left = packedLeftOrFirst(packed);
    lo = min(exact[left].min.xyz, exact[left + 1u].min.xyz);
    hi = max(exact[left].max.xyz, exact[left + 1u].max.xyz);
  } else {
    for (uint k = 0; k < packedCount(packed); ++k) {
      const BvhBox box = boxes[primitives[packedLeftOrFirst(packed) + k]];
      lo = min(lo, box.min.xyz);
      hi = max(hi, box.max.xyz);
    }
  }
  exact[node] = BvhBox(vec4(lo, 0.0), vec4(hi, 0.0));
}
