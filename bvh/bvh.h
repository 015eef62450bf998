// A BVH on the host: its nodes (with exact bounds; the device packs them for traversal, see
// bvh/packed_node.h) and the primitive indices its leaves point into, plus the SAH cost every
// builder is judged by.
#pragma once

#include <cstdint>
#include <vector>

#include "bvh/bvh_layout.h"
#include "hmblur/aabb.h"

namespace hmb::bvh {

using Node = gpu::BvhNode;

struct Bvh {
  std::vector<Node> nodes;                // empty when built over no primitives
  std::vector<uint32_t> primitiveIndices; // leaves' ranges index this array
};

// Constants of the surface area heuristic: the cost of visiting an interior node and of
// intersecting one primitive.
struct SahCosts {
  double traversal = 1.0;
  double intersection = 1.0;
};

inline bool isLeaf(const Node& node) { return node.count > 0; }
inline Aabb boundsOf(const Node& node) {
  return Aabb{{node.minX, node.minY, node.minZ}, {node.maxX, node.maxY, node.maxZ}};
}
inline void setBounds(Node& node, const Aabb& box) {
  node.minX = box.min.x, node.minY = box.min.y, node.minZ = box.min.z;
  node.maxX = box.max.x, node.maxY = box.max.y, node.maxZ = box.max.z;
}

// Expected cost of a random ray that hits the root: sum over interior nodes of
// traversal * area, plus over leaves of intersection * count * area, divided by the root's
// area. When the root has no area (every primitive a point or all in one line), every ratio
// is taken as 1. 0 for an empty BVH.
double sahCost(const Bvh& bvh, const SahCosts& costs = {});

// Number of nodes on the longest root-to-leaf path (1 for a lone leaf, 0 when empty): the
// traversal stack a kernel needs is at most this.
uint32_t depthOf(const Bvh& bvh);

}  // namespace hmb::bvh
