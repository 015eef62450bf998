#version 450
// One pass of the treelet builder's radix sort (treelet_build_layout.h), a group per tile: the
// tile's codes, in order, go to their places in their tree's range by this pass's digit. The
// place of the tile's first code of digit d is its tree's first place, plus the tree's codes of
// lower digits, plus the tree's earlier tiles' codes of digit d: every tile's counts of this
// pass are known before it starts (the last pass, or treelet_morton_codes, counted them). Within
// the tile, codes of one digit keep their order (a rank from a bit per lane), so the sort is
// stable. Each code placed is counted, for the next pass, in the tile of its new place.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "treelet_common.glsl"

layout(local_size_x = HMB_TREELET_SORT_GROUP) in;
layout(std430, binding = HMB_TREELET_BINDING_TILES) readonly buffer Tiles { TreeletTile tiles[]; };
layout(std430, binding = HMB_TREELET_BINDING_TREES) readonly buffer Trees { TreeletTree trees[]; };
layout(std430, binding = HMB_TREELET_BINDING_KEYS) buffer Keys { uint keys[]; };
layout(std430, binding = HMB_TREELET_BINDING_VALUES) buffer Values { uint values[]; };
layout(std430, binding = HMB_TREELET_BINDING_DIGIT_COUNTS) buffer DigitCounts { uint digitCounts[]; };
layout(push_constant) uniform Params { TreeletBuildParams params; };

const uint kDigits = HMB_TREELET_DIGITS;
const uint kLanes = HMB_TREELET_SORT_GROUP;
const uint kMaskWords = kLanes / 32u;
shared uint start[kDigits];               // where the tile's next code of each digit goes
shared uint lanesOf[kDigits * kMaskWords];  // a chunk's lanes holding each digit, a bit per lane
shared uint scan[kDigits];

uint digitOf(uint key, uint pass) { return (key >> (pass * HMB_TREELET_DIGIT_BITS)) & (kDigits - 1u); }

void main() {
  const uint tileIndex = foldedGroupIndex(), lane = gl_LocalInvocationIndex;
  if (tileIndex >= params.tileCount) return;  // uniform across the group
  const TreeletTile tile = tiles[tileIndex];
  const TreeletTree tree = trees[tile.tree];
  const uint pass = params.pass, n = params.primitiveCount;
  const uint treeTiles = (tree.count + HMB_TREELET_TILE - 1u) / HMB_TREELET_TILE;
  const uint counted = pass * params.tileCount * kDigits;

  // Lane d: the tree's codes of digit d, and those in its tiles before this one.
  const uint digit = lane;
  uint total = 0u, before = 0u;
  for (uint t = 0u; t < treeTiles; ++t) {
    const uint c = digitCounts[counted + (tree.firstTile + t) * kDigits + digit];
    total += c;
    before += tree.firstTile + t < tileIndex ? c : 0u;
  }
  // Exclusive sums of the totals over the digits (a scan in log2(kDigits) steps).
  scan[lane] = total;
  barrier();
  for (uint step = 1u; step < kDigits; step <<= 1u) {
    const uint add = lane >= step ? scan[lane - step] : 0u;
    barrier();
    scan[lane] += add;
    barrier();
  }
  start[digit] = tree.first + scan[digit] - total + before;

  const uint from = (pass & 1u) * n, to = n - from;
  const bool counting = pass + 1u < HMB_TREELET_SORT_PASSES;
  const uint countedNext = (pass + 1u) * params.tileCount * kDigits;
  const uint chunks = (tile.count + kLanes - 1u) / kLanes;
  for (uint chunk = 0u; chunk < chunks; ++chunk) {
    for (uint w = 0u; w < kMaskWords; ++w) lanesOf[lane * kMaskWords + w] = 0u;
    const uint k = chunk * kLanes + lane;
    const bool present = k < tile.count;
    const uint key = present ? keys[from + tile.first + k] : 0u;
    const uint value = present ? values[from + tile.first + k] : 0u;
    const uint d = digitOf(key, pass), word = lane / 32u, bit = 1u << (lane % 32u);
    barrier();
    // Every lane takes the atomic (one past the tile adds nothing): lavapipe 22.3 returned wrong
    // values from atomics some lanes of a vector skipped.
    atomicOr(lanesOf[d * kMaskWords + word], present ? bit : 0u);
    barrier();
    uint rank = bitCount(lanesOf[d * kMaskWords + word] & (bit - 1u));
    for (uint w = 0u; w < word; ++w) rank += bitCount(lanesOf[d * kMaskWords + w]);
    const uint place = start[d] + rank;
    if (present) {
      keys[to + place] = key;
      values[to + place] = value;
    }
    const uint landed = tree.firstTile + (present ? (place - tree.first) / HMB_TREELET_TILE : 0u);
    if (counting)
      atomicAdd(digitCounts[countedNext + landed * kDigits + digitOf(key, pass + 1u)], present ? 1u : 0u);
    barrier();
    uint chunkCount = 0u;
    for (uint w = 0u; w < kMaskWords; ++w) chunkCount += bitCount(lanesOf[digit * kMaskWords + w]);
    start[digit] += chunkCount;
  }
}
