#version 450
// Adds nodes of the reference's sum tree (runtime/passes/reference_sum_tree.h) held in slots,
// two at a time in the list's order, each sum into the left operand's slot: the end of a render
// (its held nodes into the total) and a merge of shards (their nodes into the nodes above).
// Each invocation owns one pixel, in every slot.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reference_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_FOLD_SUMS_GROUP) in;

layout(std430, binding = HMB_FOLD_SUMS_BINDING_SUMS) buffer Sums { vec4 sums[]; };
layout(std430, binding = HMB_FOLD_SUMS_BINDING_OPS) readonly buffer Ops { uvec4 ops[]; };
layout(push_constant) uniform Params { FoldSumsParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_FOLD_SUMS_GROUP);
  if (i >= params.pixelCount) return;
  // A run of additions into one slot keeps its sum in a register and writes it once.
  uint held = 0xffffffffu;
  vec4 sum = vec4(0.0);
  for (uint op = 0u; op < params.opCount; ++op) {
    if (ops[op].x != held) {
      if (held != 0xffffffffu) sums[held * params.pixelCount + i] = sum;
      held = ops[op].x;
      sum = sums[held * params.pixelCount + i];
    }
    sum = sum + sums[ops[op].y * params.pixelCount + i];
  }
  if (held != 0xffffffffu) sums[held * params.pixelCount + i] = sum;
}
