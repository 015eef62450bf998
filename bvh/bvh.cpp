#include "bvh/bvh.h"

#include <algorithm>
#include <utility>

namespace hmb::bvh {

double sahCost(const Bvh& bvh, const SahCosts& costs) {
  if (bvh.nodes.empty()) return 0.0;
  const double rootArea = boundsOf(bvh.nodes[HMB_BVH_ROOT]).surfaceArea();
  double cost = 0.0;
  for (const Node& node : bvh.nodes) {
    const double ratio = rootArea > 0.0 ? boundsOf(node).surfaceArea() / rootArea : 1.0;
    cost += ratio * (isLeaf(node) ? costs.intersection * node.count : costs.traversal);
  }
  return cost;
}

uint32_t depthOf(const Bvh& bvh) {
  if (bvh.nodes.empty()) return 0;
  uint32_t deepest = 0;
  std::vector<std::pair<uint32_t, uint32_t>> stack{{HMB_BVH_ROOT, 1}};  // (node, its depth)
  while (!stack.empty()) {
    const auto [index, depth] = stack.back();
    stack.pop_back();
    deepest = std::max(deepest, depth);
    const Node& node = bvh.nodes[index];
    if (isLeaf(node)) continue;
    stack.push_back({node.leftOrFirst, depth + 1});
    stack.push_back({node.leftOrFirst + 1, depth + 1});
  }
  return deepest;
}

}  // namespace hmb::bvh
