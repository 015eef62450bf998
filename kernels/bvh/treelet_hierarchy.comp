#version 450
// The treelet builder's hierarchy (treelet_build_layout.h), a group per tile, a lane per place:
// the Karras radix tree over its tree's sorted codes (as linear_hierarchy.comp, within the
// tree's range). Interior node p names its children and is named their parent; every leaf is
// marked (a count of 1), and each tree's root is told its tree.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "treelet_common.glsl"

layout(local_size_x = HMB_TREELET_SORT_GROUP) in;
layout(std430, binding = HMB_TREELET_BINDING_TILES) readonly buffer Tiles { TreeletTile tiles[]; };
layout(std430, binding = HMB_TREELET_BINDING_TREES) readonly buffer Trees { TreeletTree trees[]; };
layout(std430, binding = HMB_TREELET_BINDING_KEYS) readonly buffer Keys { uint keys[]; };
layout(std430, binding = HMB_TREELET_BINDING_NODES) buffer Nodes { TreeletNode nodes[]; };
layout(push_constant) uniform Params { TreeletBuildParams params; };

uint first, count;

// The bits places i and j of the tree share from the top of (code, place), -1 outside it.
int sharedBits(int i, int j) {
  if (j < 0 || j >= int(count)) return -1;
  const uint a = keys[first + uint(i)], b = keys[first + uint(j)];
  if (a != b) return 31 - findMSB(a ^ b);
  return 32 + 31 - findMSB(uint(i ^ j));
}

void main() {
  const uint tileIndex = foldedGroupIndex(), lane = gl_LocalInvocationIndex;
  if (tileIndex >= params.tileCount) return;  // uniform across the group
  const TreeletTile tile = tiles[tileIndex];
  first = trees[tile.tree].first;
  count = trees[tile.tree].count;
  const uint n = params.primitiveCount;
  for (uint k = lane; k < tile.count; k += HMB_TREELET_SORT_GROUP) {
    const uint place = tile.first + k;
    nodes[n + place].count = 1u;
    if (count == 1u) {
      nodes[n + place].parent = HMB_TREELET_NONE;
      nodes[n + place].tree = tile.tree;
    }
    const int i = int(place - first);
    if (i + 1 >= int(count)) continue;
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
    const uint gamma = first + uint(i + split * d + min(d, 0));
    const uint left = uint(min(i, j)) + first == gamma ? n + gamma : gamma;
    const uint right = uint(max(i, j)) + first == gamma + 1u ? n + gamma + 1u : gamma + 1u;
    nodes[place].left = left;
    nodes[place].right = right;
    nodes[left].parent = place;
    nodes[right].parent = place;
    if (i == 0) {
      nodes[place].parent = HMB_TREELET_NONE;
      nodes[place].tree = tile.tree;
    }
  }
}
