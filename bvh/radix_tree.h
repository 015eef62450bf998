// Morton codes and the Karras radix tree over them (Karras 2012, "Maximizing Parallelism in the
// Construction of BVHs, Octrees, and k-d Trees"): the host's twin of what the linear and
// treelet builders' kernels compute (kernels/bvh/linear_hierarchy.comp, treelet_hierarchy.comp),
// and the treelet builder's whole math, the reference its kernels are tested against.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "hmblur/aabb.h"

namespace hmb::bvh {

// The radix tree over sorted codes, equal codes told apart by their places: for each interior
// node i in [0, n - 1) its (left, right) children, Karras-named (leaf k is node n - 1 + k).
std::vector<glm::uvec2> radixTree(std::span<const uint32_t> sortedCodes);

// The treelet builder's Morton code of each box (kernels/bvh/treelet_morton_codes.comp): the
// cell of its centre, 1024 an axis, in the bounds of the boxes' centres (an empty or non-finite
// box's centre is the origin). The kernel divides where this does, and Vulkan lets a division be
// off by 2.5 ulp, so a code on a cell's edge may differ by a cell.
std::vector<uint32_t> treeletMortonCodes(std::span<const Aabb> boxes);
// The cell a Morton code names (gpu::mortonCode's inverse).
glm::uvec3 mortonCell(uint32_t code);

// The treelet builder's tree (kernels/bvh/treelet_optimize.comp, treelet_pack.comp) over boxes
// in a sorted order: the radix tree over the sorted codes, each node finished after its children
// (its treelet of up to HMB_TREELET_LEAVES subtrees merged again, the closest pair first, where
// that costs less and is no deeper; a leaf of up to maxLeaf primitives where that costs less),
// laid out as the device lays out a build's one tree: the root at 0, children in pairs, a node's
// children after it, then its left child's nodes, then its right child's.
Bvh buildTreeletTree(std::span<const Aabb> boxes, std::span<const uint32_t> sortedCodes,
                     std::span<const uint32_t> sortedPrimitives, uint32_t maxLeaf);

// Both: the codes, stably sorted, and the tree over them.
Bvh buildTreeletReference(std::span<const Aabb> boxes, uint32_t maxLeaf);

}  // namespace hmb::bvh
