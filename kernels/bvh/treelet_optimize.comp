#version 450
// The treelet builder's bottom-up pass (treelet_build_layout.h): a lane per leaf writes its
// primitive's box and climbs. At each node the first of its two lanes to arrive stops; the
// second finishes the node, whose subtrees are then final:
// - its box, its primitive count, and its SAH cost as a split or, for up to maxLeaf primitives,
//   as one leaf, whichever is cheaper (area-weighted: a visit costs 1, a primitive 1);
// - its treelet rebuilt: the node's largest subtrees, up to HMB_TREELET_LEAVES of them (a
//   subtree is opened where its box is the largest of those not yet opened), merged again pair
//   by pair, the pair whose union has the smallest area first, into the treelet's own interior
//   nodes. The rebuild is kept where it costs less and is no deeper.
// At a tree's root the lane takes the place of the tree's nodes in the output. So every node is
// finished once, after its subtrees, and no lane waits for another.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "../shared/indexing.glsl"
#include "treelet_common.glsl"

layout(local_size_x = HMB_TREELET_GROUP) in;
layout(std430, binding = HMB_TREELET_BINDING_BOXES) readonly buffer Boxes { BvhBox boxes[]; };
layout(std430, binding = HMB_TREELET_BINDING_VALUES) readonly buffer Values { uint values[]; };
// A lane reads what another wrote before the atomic that let it on.
layout(std430, binding = HMB_TREELET_BINDING_NODES) coherent buffer Nodes { TreeletNode nodes[]; };
layout(std430, binding = HMB_TREELET_BINDING_TREES) writeonly buffer Trees { TreeletTree trees[]; };
layout(std430, binding = HMB_TREELET_BINDING_COUNTERS) buffer Counters { BvhBuildCounters counters; };
layout(push_constant) uniform Params { TreeletBuildParams params; };

// As linear_bounds.comp: on lavapipe 22.3 every lane takes every round (its atomic adds 0 once
// it stopped), elsewhere a lane leaves when it stops.
layout(constant_id = HMB_SPEC_TREELET_UNIFORM_ROUNDS) const bool kUniformRounds = false;

const uint kLeaves = HMB_TREELET_LEAVES;

// A subtree as the treelet sees it.
vec3 lo[kLeaves], hi[kLeaves];
float cost[kLeaves];
uint count[kLeaves], below[kLeaves], height[kLeaves], id[kLeaves];

void load(uint slot, uint node) {
  lo[slot] = nodes[node].lo.xyz;
  hi[slot] = nodes[node].hi.xyz;
  cost[slot] = nodes[node].lo.w;
  count[slot] = nodes[node].count;
  below[slot] = nodes[node].below;
  height[slot] = nodes[node].height;
  id[slot] = node;
}

// Slot a becomes the node over slots a and b: its box, count and cheaper form.
void merge(uint a, uint b) {
  const float noLeaf = uintBitsToFloat(0x7f800000u);  // +inf: no leaf holds more than maxLeaf primitives
  lo[a] = min(lo[a], lo[b]);
  hi[a] = max(hi[a], hi[b]);
  const float area = halfArea(lo[a], hi[a]);
  precise const float split = area + cost[a] + cost[b];
  count[a] += count[b];
  precise const float asLeaf = count[a] <= params.maxLeaf ? area * float(count[a]) : noLeaf;
  if (asLeaf <= split) {
    cost[a] = asLeaf;
    below[a] = 0u;
    height[a] = 1u;
  } else {
    cost[a] = split;
    below[a] = 2u + below[a] + below[b];
    height[a] = 1u + max(height[a], height[b]);
  }
}

void store(uint slot, uint node, uint left, uint right) {
  nodes[node].lo = vec4(lo[slot], cost[slot]);
  nodes[node].hi = vec4(hi[slot], 0.0);
  nodes[node].left = left;
  nodes[node].right = right;
  nodes[node].count = count[slot];
  nodes[node].below = below[slot];
  nodes[node].height = height[slot];
  nodes[left].parent = node;
  nodes[right].parent = node;
}

// Finishes interior node p, whose children are final.
void finish(uint p) {
  const uint n = params.primitiveCount;
  const uint left = nodes[p].left, right = nodes[p].right;
  load(0u, left);
  load(1u, right);
  merge(0u, 1u);
  store(0u, p, left, right);
  if (count[0] < 3u) return;
  const float built = cost[0];
  const uint builtHeight = height[0];

  // The treelet: open its largest subtree until it has kLeaves (interior nodes: p first).
  uint interior[kLeaves - 1u];
  interior[0] = p;
  load(0u, left);
  load(1u, right);
  uint leaves = 2u;
  for (; leaves < kLeaves; ++leaves) {
    uint widest = kLeaves;
    float widestArea = -1.0;
    for (uint s = 0u; s < leaves; ++s) {
      const float area = halfArea(lo[s], hi[s]);
      if (id[s] < n && area > widestArea) {
        widest = s;
        widestArea = area;
      }
    }
    if (widest == kLeaves) break;  // only primitives left
    const uint opened = id[widest];
    interior[leaves - 1u] = opened;
    load(widest, nodes[opened].left);
    load(leaves, nodes[opened].right);
  }

  // Merged again, the closest pair first, into the treelet's interior nodes (the last merge into
  // p): merge m makes mergedInto[m] over the nodes merges[m].
  uvec2 merges[kLeaves - 1u];
  uint mergedInto[kLeaves - 1u];
  uint slotIds[kLeaves];
  for (uint s = 0u; s < leaves; ++s) slotIds[s] = id[s];
  uint live = leaves;
  for (uint m = 0u; m + 1u < leaves; ++m) {
    uint bestA = 0u, bestB = 1u;
    float bestArea = uintBitsToFloat(0x7f800000u);
    for (uint a = 0u; a + 1u < live; ++a)
      for (uint b = a + 1u; b < live; ++b) {
        const float area = halfArea(min(lo[a], lo[b]), max(hi[a], hi[b]));
        if (area < bestArea) {
          bestArea = area;
          bestA = a;
          bestB = b;
        }
      }
    const uint node = m + 2u == leaves ? p : interior[m + 1u];
    merges[m] = uvec2(slotIds[bestA], slotIds[bestB]);
    merge(bestA, bestB);
    slotIds[bestA] = node;
    // The last live slot fills b's.
    --live;
    lo[bestB] = lo[live];
    hi[bestB] = hi[live];
    cost[bestB] = cost[live];
    count[bestB] = count[live];
    below[bestB] = below[live];
    height[bestB] = height[live];
    slotIds[bestB] = slotIds[live];
    mergedInto[m] = node;
  }
  if (!(cost[0] < built) || height[0] > builtHeight) return;

  // Kept: the merges again in their order, each node stored from its children as stored.
  for (uint m = 0u; m + 1u < leaves; ++m) {
    const uint node = mergedInto[m], a = merges[m].x, b = merges[m].y;
    load(0u, a);
    load(1u, b);
    merge(0u, 1u);
    store(0u, node, a, b);
  }
}

void main() {
  const uint place = linearInvocationIndex(HMB_TREELET_GROUP), n = params.primitiveCount;
  bool climbing = place < n && nodes[n + place].count != 0u;  // places outside every tree: no leaf
  uint node = climbing ? n + place : 0u;
  if (climbing) {
    const BvhBox box = boxes[values[place]];
    const bool empty = !all(lessThanEqual(box.min.xyz, box.max.xyz));
    nodes[node].lo = vec4(box.min.xyz, empty ? 0.0 : halfArea(box.min.xyz, box.max.xyz));
    nodes[node].hi = vec4(box.max.xyz, 0.0);
    nodes[node].below = 0u;
    nodes[node].height = 1u;
  }
  uint parent = climbing ? nodes[node].parent : HMB_TREELET_NONE;
  climbing = parent != HMB_TREELET_NONE;
  for (uint round = 0u; round < HMB_TREELET_MAX_HEIGHT && (kUniformRounds || climbing); ++round) {
    memoryBarrierBuffer();
    const uint arrived = atomicAdd(nodes[climbing ? parent : n].visits, climbing ? 1u : 0u);
    memoryBarrierBuffer();
    const bool second = climbing && arrived != 0u;
    if (second) {
      node = parent;
      finish(node);
      memoryBarrierBuffer();
      parent = nodes[node].parent;
      if (parent == HMB_TREELET_NONE) {
        // The root: its tree's nodes go after every root, in the order the trees finish.
        const uint tree = nodes[node].tree;
        trees[tree].nodeBase = atomicAdd(counters.nodeCount, nodes[node].below);
      }
    }
    climbing = second && parent != HMB_TREELET_NONE;
  }
}
