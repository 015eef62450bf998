#version 450
// The linear builder's second pass (linear_bvh_layout.h): a lane per interior node i of the
// radix tree over the sorted codes (Karras 2012), its range of codes and the split inside it
// found from the codes alone; it names its two children and is named their parent. Equal codes
// are told apart by their places, so every range splits.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "linear_bvh_layout.h"

layout(local_size_x = HMB_LINEAR_BVH_GROUP) in;
layout(std430, binding = HMB_LINEAR_HIERARCHY_BINDING_CODES) readonly buffer Codes { uint codes[]; };
layout(std430, binding = HMB_LINEAR_HIERARCHY_BINDING_LINKS) buffer Links { LinearBvhLink links[]; };
layout(push_constant) uniform Params { LinearBvhParams params; };

// The bits places i and j share from the top of (code, place), -1 outside the codes.
int sharedBits(int i, int j) {
  const int n = int(params.primitiveCount);
  if (j < 0 || j >= n) return -1;
  const uint a = codes[i], b = codes[j];
  if (a != b) return 31 - findMSB(a ^ b);
  return 32 + 31 - findMSB(uint(i ^ j));
}

void main() {
  const uint node = linearInvocationIndex(HMB_LINEAR_BVH_GROUP), n = params.primitiveCount;
  if (n < 2u || node >= n - 1u) return;
  const int i = int(node);
  // The range's direction, its other end j, then the split: the last place sharing more bits
  // with i than j does.
  const int d = sharedBits(i, i + 1) > sharedBits(i, i - 1) ? 1 : -1;
  const int least = sharedBits(i, i - d);
  int reach = 2;
  while (sharedBits(i, i + reach * d) > least) reach *= 2;
  int length = 0;
  for (int step = reach / 2; step >= 1; step /= 2)
    if (sharedBits(i, i + (length + step) * d) > least) length += step;
  const int j = i + length * d;
  const int rangeBits = sharedBits(i, j);
  int split = 0;
  for (int step = (length + 1) / 2;; step = (step + 1) / 2) {
    if (sharedBits(i, i + (split + step) * d) > rangeBits) split += step;
    if (step == 1) break;
  }
  const int gamma = i + split * d + min(d, 0);
  const uint leaves = n - 1u;  // leaf k is node n - 1 + k
  const uint left = min(i, j) == gamma ? leaves + uint(gamma) : uint(gamma);
  const uint right = max(i, j) == gamma + 1 ? leaves + uint(gamma + 1) : uint(gamma + 1);
  links[node].left = left;
  links[node].right = right;
  links[left].parent = node;
  links[right].parent = node;
  if (node == 0u) links[0].parent = HMB_LINEAR_BVH_NONE;
}
