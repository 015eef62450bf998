// Layouts of the BVH builder's kernels: triangle_bounds / instance_motion_bounds (primitive
// boxes) -> begin_build (one root task per tree) -> build_level, once per tree level, with
// size_build_dispatch sizing the next level's indirect dispatch -> build_small_tasks, the
// subtrees of small tasks whole.
//
// The build is top-down binned SAH, level by level: one workgroup per task (a node and its
// primitive range) bins the range's centroids, picks the cheapest split on any axis, and
// partitions the range into its two children, which become the next level's tasks. Several
// trees (one per mesh) build in the same levels; tree r's root is node r. Each node is
// written twice: with exact float bounds, which the build reads, and packed in its tree's
// frame (kernels/bvh/packed_node.glsl), which traversal reads.
#ifndef HMB_KERNELS_BVH_BVH_BUILD_LAYOUT_H
#define HMB_KERNELS_BVH_BVH_BUILD_LAYOUT_H

#include "../../bvh/bvh_layout.h"
#include "../shared/glsl_cpp.h"

#define HMB_BVH_BUILD_GROUP 64
// build_level's workgroup, one task each, shaped per device (runtime/passes/bvh_build_pass.h,
// BvhBuildShape) through two specialization constants:
// - on CPU devices (lavapipe), 8 lanes, its SIMD width (64 lanes made small tasks slower
//   there), and a task of at least HMB_BVH_LANE_BINS_MIN primitives bins into a copy of the
//   bins per lane, without atomics: lavapipe runs each shared atomic lane by lane as a
//   compare-exchange loop, which made binning of large tasks slower; smaller ones bin with
//   shared atomics, which costs less than clearing and merging the copies
//   (bench/results/bvh-build-shape/);
// - on GPUs, a warp or wave (the subgroup size, at least 32) binning with shared atomics, which
//   GPUs run natively; per-lane copies would need 1.5 KiB of shared memory per lane.
#define HMB_BVH_LEVEL_GROUP 8
#define HMB_BVH_LANE_BINS_MIN 64u
#define HMB_SPEC_BVH_LEVEL_GROUP 0  // the workgroup's size (local_size_x_id)
#define HMB_SPEC_BVH_LANE_BINS 1    // bool: large tasks bin into per-lane copies
// The most primitives one tree may have: lavapipe stops any invocation's loops after 65535
// iterations in all, and a root task's lanes loop twice over count / (8 lanes * 8 unrolled).
#define HMB_BVH_MAX_TREE_PRIMITIVES 2000000u
// Centroid bins per axis. 16 keep the SAH cost within a few percent of a full sweep.
#define HMB_BVH_BINS 16
// A level task bins a sample of its primitives: every s-th, s = count / HMB_BVH_BIN_SAMPLE
// (at least 1), so binning sees this many to twice as many; the partition still places every
// primitive and counts the children exactly.
#define HMB_BVH_BIN_SAMPLE 4096u
// A task of at most this many primitives is not split level by level: build_small_tasks, one
// invocation per task after the levels, builds its whole subtree, binning each node's
// primitives into HMB_BVH_SMALL_TASK_BINS bins per axis held in registers. The deep levels'
// thousands of tiny tasks each cost build_level a workgroup and its bins' set-up. 64 measured
// faster than 32 at the same SAH cost; 128 was no faster and raised the SAH cost
// (bench/results/bvh-build-shape/).
#define HMB_BVH_SMALL_TASK 64u
#define HMB_BVH_SMALL_TASK_GROUP 64
#define HMB_BVH_SMALL_TASK_BINS 8
// The largest small task is a specialization constant of begin_build, build_level and
// build_small_tasks (the size of the latter's arrays), HMB_BVH_SMALL_TASK unless the build asks
// otherwise (BvhBuildShape::smallTask). A top level of up to HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU
// instances is one invocation's work on a CPU device: there a level costs its two dispatches,
// and one lane builds bistro's 321 instances' whole tree faster than its levels do
// (bench/results/bvh-top-level/). A GPU keeps HMB_BVH_SMALL_TASK, as its lanes run slowly alone.
#define HMB_SPEC_BVH_SMALL_TASK 0        // begin_build's and build_small_tasks'
#define HMB_SPEC_BVH_LEVEL_SMALL_TASK 2  // build_level's
// bool, build_small_tasks': its nodes' bounds are packed after it, by pack_deferred_nodes,
// a lane per node; the CPU top level's tasks do so. One invocation building a task of
// hundreds packs a node's six bounds in turn, and their searches' loops count against
// lavapipe's budget of loop iterations (BvhBuildPass::smallTaskDepthBound). Such a node's
// packed x word is HMB_BVH_PACK_LATER (a lower step above the upper one, as no box packs:
// an empty box packs HMB_BVH_QUANTUM_MAX over 0) and its y word its tree, until it is packed.
#define HMB_SPEC_BVH_PACK_LATER 1
#define HMB_BVH_PACK_LATER 0x0000fffeu
#define HMB_BVH_PACK_GROUP 64
// A tree over some primitives, kept from frame to frame, with a few others inserted into it in
// each (BvhBuildPass::recordKeptWithInsertions): the kept tree is built over the first
// roots[0].y places of a primitive order the host gives, its exact nodes saved; insert_primitives
// restores them and inserts the order's later places one by one, each a new pair of nodes past
// the kept tree's (at most 2 k + 1 for k kept primitives).
#define HMB_BVH_MAX_INSERTED 32u
#define HMB_BUILD_BINDING_KEPT_NODES 7  // insert_primitives: the kept tree's exact nodes, as built
#define HMB_INSERT_BINDING_COUNT 8
// BvhBuildParams::flags
#define HMB_BVH_BUILD_GIVEN_ORDER 1u  // begin_build keeps the primitive order the host wrote
#define HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU 512u
// Leaves of mesh trees hold at most this many primitives (as the CPU reference builder's
// default); each build names its own limit (BvhBuildParams::maxLeaf).
#define HMB_BVH_MAX_LEAF 4u
// The top level holds one instance per leaf: entering an instance (its transform, the ray's
// set-up in its space) costs more than the node visits that keep instances apart, and bistro's
// reveal rays took 6% less time than with leaves of up to four.
#define HMB_BVH_MAX_INSTANCE_LEAF 1u
// No node lies more than this many levels below its root, so a walk that keeps one pending
// subtree per level (kernels/trace/closest_hit.glsl) never runs out of stack and needs no
// stackless fallback. The builder keeps it by halving a range (a median split) wherever the
// SAH split's larger side could not end within the levels left; 2^21 primitives need 21.
// (BvhBuildParams::maxDepth carries it, so that tests can build under a tighter bound.)
#define HMB_BVH_MAX_DEPTH 64u

// triangle_bounds
#define HMB_TRIANGLE_BOUNDS_BINDING_POSITIONS 0  // vec4 per vertex (xyz)
#define HMB_TRIANGLE_BOUNDS_BINDING_TRIANGLES 1  // uvec4 (v0, v1, v2, unused) per triangle
#define HMB_TRIANGLE_BOUNDS_BINDING_BOXES 2      // BvhBox per triangle
#define HMB_TRIANGLE_BOUNDS_BINDING_COUNT 3

// deformed_leaf_triangles
#define HMB_DEFORMED_LEAVES_BINDING_VERTICES 0        // GpuVertex per mesh vertex (deformed)
#define HMB_DEFORMED_LEAVES_BINDING_PRIMITIVES 1      // the leaf order: triangle of each entry
#define HMB_DEFORMED_LEAVES_BINDING_LEAF_TRIANGLES 2  // 3 vec4 per entry (xyz rewritten, w kept)
#define HMB_DEFORMED_LEAVES_BINDING_BOXES 3           // BvhBox per triangle
#define HMB_DEFORMED_LEAVES_BINDING_COUNT 4

// begin_build, build_level and size_build_dispatch share one binding table.
#define HMB_BUILD_BINDING_BOXES 0       // BvhBox per primitive
#define HMB_BUILD_BINDING_ROOTS 1       // uvec2 (first primitive, count) per tree
#define HMB_BUILD_BINDING_PRIMITIVES 2  // uint[2 * primitiveCount]: the final array, then a scratch copy
#define HMB_BUILD_BINDING_NODES 3       // BvhNode[]: exact bounds, the build's working copy
// The task queue: BvhBuildCounters (its head: the levels' task counts and indirect
// dispatches), then BvhBuildTask[3 * taskCapacity] from byte sizeof(BvhBuildCounters) (a
// multiple of a task's 16-byte alignment): this level's, the next level's, and the small
// tasks build_small_tasks finishes.
#define HMB_BUILD_BINDING_TASKS 4
#define HMB_BUILD_BINDING_PACKED_NODES 5  // BvhPackedNode[]: the nodes as traversal reads them
#define HMB_BUILD_BINDING_FRAMES 6        // BvhFrame per tree: what its packed bounds count steps in
#define HMB_BUILD_BINDING_COUNT 7
// The boxes are read as a uniform texel buffer (bvh_build_common.glsl), counted in kernels/manifest.h.

// refit_parents and refit_places (once per build: the trees keep only the way down), then per
// refit refit_bounds (once per depth, deepest first, over that depth's nodes) and refit_pack: a
// built tree's bounds from new primitive boxes, its topology and primitive order kept
// (deforming meshes). Each kernel binds only what it uses (at most 6 buffers).
#define HMB_REFIT_BINDING_BOXES 0         // BvhBox per primitive, the new ones
#define HMB_REFIT_BINDING_ROOTS 1         // uvec2 (first primitive, count) per tree
#define HMB_REFIT_BINDING_PRIMITIVES 2    // the built primitive order the leaves index
#define HMB_REFIT_BINDING_PACKED_NODES 3  // rewritten: bounds in the tree's new frame
#define HMB_REFIT_BINDING_FRAMES 4        // rewritten: from each root's new box
#define HMB_REFIT_BINDING_EXACT 5         // BvhBox per node: the refitted exact bounds (scratch)
#define HMB_REFIT_BINDING_PARENTS 6       // uint per node
#define HMB_REFIT_BINDING_PLACES 7        // uvec2 per node: its depth (steps from its root) and its root
#define HMB_REFIT_BINDING_ORDER 8         // uint per node: the nodes by depth (the host sorts the places)
#define HMB_REFIT_PARENTS_BINDINGS 3      // roots, packed nodes, parents
#define HMB_REFIT_PLACES_BINDINGS 2       // parents, places
#define HMB_REFIT_BOUNDS_BINDINGS 6       // boxes, roots, primitives, packed nodes, exact, order
#define HMB_REFIT_PACK_BINDINGS 6         // roots, packed nodes, frames, exact, places, order
#define HMB_REFIT_GROUP 64

HMB_GPU_BEGIN

struct BvhRefitParams {
  uint nodeCount;
  uint treeCount;  // roots are nodes 0..treeCount-1
  uint first;      // refit_bounds: its depth's first node in the order; refit_pack: 0
  uint count;      // refit_bounds: that depth's nodes; refit_pack: all the order's
};

// A primitive's bounds (w unused). Empty: min > max.
struct BvhBox {
  vec4 min;
  vec4 max;
};

struct BvhBuildParams {
  uint primitiveCount;
  uint treeCount;
  uint taskCapacity;  // tasks one level can hold (each half of the task buffer)
  uint level;         // build_level / size_build_dispatch: the level being built (0 = roots)
  uint maxLeaf;       // the most primitives a leaf may hold (>= 1)
  uint maxDepth;      // levels a node may lie below its root: HMB_BVH_MAX_DEPTH, or fewer in tests
  uint pad;
  uint flags;         // HMB_BVH_BUILD_*
};

// A node still to split and the primitives below it; its bounds are already in the node.
struct BvhBuildTask {
  uint node;
  uint first;  // range of the primitive arrays
  uint count;
  uint tree;         // whose frame the node's children are packed in
  vec4 centroidMin;  // bounds of the range's box centres; small tasks: w the node's level
  vec4 centroidMax;  // small tasks: w the half of the primitive array the range is in (0, 1)
};

// Indirect dispatch arguments and task counts of two levels in turn (index: level & 1).
struct BvhBuildCounters {
  uvec4 dispatch[2];    // xyz: groups of build_level for a level with that parity
  uvec4 smallDispatch;  // xyz: groups of build_small_tasks
  uint taskCount[2];    // tasks of a level with that parity
  uint smallTaskCount;
  uint nodeCount;  // nodes allocated (trees' roots included)
  uint levels;     // deepest level that had tasks, plus one
  uint leafCount;
  uint pad0;
  uint pad1;
};

HMB_GPU_END

HMB_CHECK_SIZE(BvhBox, 32)
HMB_CHECK_SIZE(BvhBuildParams, 32)
HMB_CHECK_SIZE(BvhBuildTask, 48)
HMB_CHECK_SIZE(BvhBuildCounters, 80)
HMB_CHECK_SIZE(BvhRefitParams, 16)

#endif
