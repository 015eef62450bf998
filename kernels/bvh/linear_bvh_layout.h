// Layouts of the linear BVH builder (Karras 2012), the top level's builder under the GPU
// profile: a constant number of dispatches whatever the instance count, where the binned
// builder records two a level. One tree over up to HMB_LINEAR_BVH_MAX_PRIMITIVES primitives,
// a primitive a leaf (the top level's instances):
//   linear_sort_keys   one workgroup: the centroids' bounds, a 30-bit Morton code per primitive,
//                      and a stable radix sort of the codes (the primitive order the leaves index)
//   linear_hierarchy   a lane per interior node: its range of sorted codes and its split, from the
//                      codes alone (the node's children and the children's parent)
//   linear_bounds      a lane per leaf, up the tree: the second lane to reach a node bounds it
//                      (an atomic count a node; no lane waits for another)
//   linear_pack        a lane per node: the tree's frame from the root's box, and the node packed
//                      in it where traversal reads it, children of interior node i at 2 i + 1 and
//                      2 i + 2, the root at 0
// Nodes are named as Karras names them: interior i in [0, n - 1), leaf j at n - 1 + j (a tree
// of one primitive: its leaf is node 0, the root). Equal codes split by their places, so a
// tree over n <= 2^16 primitives is at most 32 + 16 levels deep, within HMB_BVH_MAX_DEPTH.
#ifndef HMB_KERNELS_BVH_LINEAR_BVH_LAYOUT_H
#define HMB_KERNELS_BVH_LINEAR_BVH_LAYOUT_H

#include "../shared/glsl_cpp.h"
#include "bvh_build_layout.h"

#define HMB_LINEAR_BVH_MAX_PRIMITIVES 65536u
// linear_sort_keys' one group: each lane sorts a run of the codes, 4 bits a pass, and the lanes'
// digit counts (lanes x 16) fit 8 KiB of shared memory.
#define HMB_LINEAR_SORT_GROUP 128
#define HMB_LINEAR_SORT_DIGIT_BITS 4u
#define HMB_LINEAR_SORT_PASSES 8u
#define HMB_LINEAR_BVH_GROUP 64
#define HMB_LINEAR_BVH_NONE 0xffffffffu  // the root's parent
#define HMB_SPEC_LINEAR_UNIFORM_ROUNDS 0  // linear_bounds: bool, every lane takes every round

// linear_sort_keys
#define HMB_LINEAR_SORT_BINDING_BOXES 0       // BvhBox per primitive
#define HMB_LINEAR_SORT_BINDING_CODES 1       // uint[2 n]: the sorted codes in the first half, scratch after
#define HMB_LINEAR_SORT_BINDING_PRIMITIVES 2  // uint[2 n]: the sorted order in the first half, scratch after
#define HMB_LINEAR_SORT_BINDING_COUNT 3
// linear_hierarchy
#define HMB_LINEAR_HIERARCHY_BINDING_CODES 0  // the sorted codes
#define HMB_LINEAR_HIERARCHY_BINDING_LINKS 1  // LinearBvhLink per node
#define HMB_LINEAR_HIERARCHY_BINDING_COUNT 2
// linear_bounds
#define HMB_LINEAR_BOUNDS_BINDING_BOXES 0
#define HMB_LINEAR_BOUNDS_BINDING_PRIMITIVES 1
#define HMB_LINEAR_BOUNDS_BINDING_LINKS 2
#define HMB_LINEAR_BOUNDS_BINDING_EXACT 3  // BvhBox per node
#define HMB_LINEAR_BOUNDS_BINDING_COUNT 4
// linear_pack
#define HMB_LINEAR_PACK_BINDING_LINKS 0
#define HMB_LINEAR_PACK_BINDING_EXACT 1
#define HMB_LINEAR_PACK_BINDING_FRAMES 2        // BvhFrame of the tree
#define HMB_LINEAR_PACK_BINDING_PACKED_NODES 3  // BvhPackedNode per node, as traversal reads them
#define HMB_LINEAR_PACK_BINDING_COUNT 4

HMB_GPU_BEGIN

struct LinearBvhParams {
  uint primitiveCount;
  uint pad0;
  uint pad1;
  uint pad2;
};

// A node's links (cleared to 0 before the build, but `parent`, which linear_hierarchy writes).
struct LinearBvhLink {
  uint parent;  // HMB_LINEAR_BVH_NONE for the root
  uint left;    // interior nodes: the children, Karras-named
  uint right;
  uint visits;  // linear_bounds: lanes that reached the node
};

// 10 bits of a coordinate in [0, 1023] spread to every third bit.
HMB_SHARED uint spreadMortonBits(uint v) {
  v &= 0x3ffu;
  v = (v | (v << 16u)) & 0x030000ffu;
  v = (v | (v << 8u)) & 0x0300f00fu;
  v = (v | (v << 4u)) & 0x030c30c3u;
  v = (v | (v << 2u)) & 0x09249249u;
  return v;
}

// The Morton code of a point's cell in a 1024^3 grid (x in the highest of each three bits).
HMB_SHARED uint mortonCode(uvec3 cell) {
  return (spreadMortonBits(cell.x) << 2u) | (spreadMortonBits(cell.y) << 1u) | spreadMortonBits(cell.z);
}

HMB_GPU_END

HMB_CHECK_SIZE(LinearBvhParams, 16)
HMB_CHECK_SIZE(LinearBvhLink, 16)

#endif
