// Layouts of the treelet builder, the mesh builder under the GPU profile: a constant number of
// dispatches whatever the size, where the binned builder (bvh_build_layout.h) records two a
// level and waits on the host between batches of levels. One or more trees over one array of
// primitive boxes, tree r over the range roots[r] and rooted at node r, written in the node
// format traversal reads (packed_node.glsl), as the binned builder writes it:
//   treelet_centroid_bounds  a group per tile: each tree's centroid bounds (atomics)
//   treelet_morton_codes     a group per tile: a 30-bit Morton code per primitive in its tree's
//                            centroid bounds, and each tile's count of the first digit
//   treelet_sort_pass        x4, a group per tile: one stable pass of a radix sort, 8 bits a
//                            pass, within each tree's range; it counts the next pass's digits
//                            by the tile each code lands in, so no pass needs a scan of its own
//   treelet_hierarchy        a lane per place: the Karras radix tree over each tree's codes
//   treelet_optimize         a lane per leaf, up the tree: the second lane to reach a node
//                            bounds it, rebuilds the treelet below it (its largest subtrees,
//                            up to HMB_TREELET_LEAVES, merged again pair by pair, the pair
//                            with the smallest box first) where that lowers the SAH cost
//                            without deepening the tree, and decides whether the node is
//                            cheaper as a leaf of up to maxLeaf primitives
//   treelet_pack             a lane per node: its place in the output (children in pairs, a
//                            tree's nodes after every root), its primitives' places, packed
// Tiles are runs of at most HMB_TREELET_TILE places inside one tree: a tree's codes never leave
// its range, so a tile's group finds where its codes go from the counts of its tree's tiles
// alone. No lane waits on another: lanes meet at a node through an atomic count, and the
// second goes on. Nodes are named as in the Karras tree: interior node p (the place p of a
// tree's range, all but its last) and leaf n + p (n the primitive count).
#ifndef HMB_KERNELS_BVH_TREELET_BUILD_LAYOUT_H
#define HMB_KERNELS_BVH_TREELET_BUILD_LAYOUT_H

#include "../shared/glsl_cpp.h"
#include "bvh_build_layout.h"

#define HMB_TREELET_TILE 4096u
#define HMB_TREELET_SORT_GROUP 256
#define HMB_TREELET_DIGIT_BITS 8u
#define HMB_TREELET_DIGITS 256u
#define HMB_TREELET_SORT_PASSES 4u  // 30-bit codes: 8 + 8 + 8 + 6 bits
#define HMB_TREELET_GROUP 64
// A treelet's leaves: each merge of the rebuild looks at every pair left, so a lane's rounds
// stay within lavapipe 22.3's loop budget up the deepest tree (HMB_TREELET_MAX_HEIGHT nodes).
#define HMB_TREELET_LEAVES 9
#define HMB_TREELET_NONE 0xffffffffu  // a root's parent
// Every tree is at most this many nodes deep: a level of the Karras tree splits at least one
// bit of (30-bit code, 21-bit place) apart, and a rebuilt treelet is kept only where the
// subtree gets no deeper.
#define HMB_TREELET_MAX_HEIGHT 52u
#define HMB_SPEC_TREELET_UNIFORM_ROUNDS 0  // treelet_optimize: bool, every lane takes every round

// Each kernel binds what it reads of one table.
#define HMB_TREELET_BINDING_BOXES 0          // BvhBox per primitive
#define HMB_TREELET_BINDING_TILES 1          // TreeletTile per tile
#define HMB_TREELET_BINDING_TREES 2          // TreeletTree per tree
#define HMB_TREELET_BINDING_KEYS 3           // uint[2 n]: the codes, sorted into the first half
#define HMB_TREELET_BINDING_VALUES 4         // uint[2 n]: their primitives, likewise
#define HMB_TREELET_BINDING_DIGIT_COUNTS 5   // uint[passes][tiles][digits]
#define HMB_TREELET_BINDING_NODES 6          // TreeletNode[2 n]
#define HMB_TREELET_BINDING_COUNTERS 7       // BvhBuildCounters (nodes, leaves, levels)
#define HMB_TREELET_BINDING_EXACT_NODES 8    // BvhNode per output node, exact bounds
#define HMB_TREELET_BINDING_PACKED_NODES 9   // BvhPackedNode per output node
#define HMB_TREELET_BINDING_FRAMES 10        // BvhFrame per tree
#define HMB_TREELET_BINDING_PRIMITIVES 11    // the primitive order the leaves index
#define HMB_TREELET_BOUNDS_BINDINGS 3
#define HMB_TREELET_CODES_BINDINGS 6
#define HMB_TREELET_SORT_BINDINGS 5
#define HMB_TREELET_HIERARCHY_BINDINGS 4
#define HMB_TREELET_OPTIMIZE_BINDINGS 5
#define HMB_TREELET_PACK_BINDINGS 8

HMB_GPU_BEGIN

struct TreeletBuildParams {
  uint primitiveCount;
  uint treeCount;
  uint tileCount;
  uint pass;     // treelet_sort_pass: which digit (0 lowest)
  uint maxLeaf;  // the most primitives a leaf may hold
  uint pad0;
  uint pad1;
  uint pad2;
};

// A run of places inside one tree, sorted by one group.
struct TreeletTile {
  uint tree;
  uint first;  // places first .. first + count - 1
  uint count;
  uint pad;
};

// A tree's range and tiles (written by the host), its centroids' bounds (ordered floats,
// shared/ordered_float.glsl) and where its nodes start in the output.
struct TreeletTree {
  uint first;      // its primitives' places
  uint count;
  uint firstTile;  // its tiles: firstTile .. firstTile + ceil(count / HMB_TREELET_TILE) - 1
  uint nodeBase;   // treelet_optimize: the output place of its root's children
  uint centroidLow[4];   // x, y, z (one array, so that atomics take a member)
  uint centroidHigh[4];
};

// A node of the binary tree under construction (cleared to 0 before the build).
struct TreeletNode {
  vec4 lo;     // xyz: bounds; w: the subtree's SAH cost (area-weighted, unnormalized)
  vec4 hi;     // xyz
  uint parent;  // HMB_TREELET_NONE for a root
  uint left;    // interior: the children (0: no interior node at this place)
  uint right;
  uint visits;  // treelet_optimize: lanes that reached the node
  uint count;   // primitives below (a leaf: 1; 0: no node)
  uint below;   // output nodes below it (0 where it is output as a leaf)
  uint height;  // nodes on its longest path down, as output
  uint tree;    // a root: its tree
};

HMB_GPU_END

HMB_CHECK_SIZE(TreeletBuildParams, 32)
HMB_CHECK_SIZE(TreeletTile, 16)
HMB_CHECK_SIZE(TreeletTree, 48)
HMB_CHECK_SIZE(TreeletNode, 64)

#endif
