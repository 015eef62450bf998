#include "bvh/reference_builder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace hmb::bvh {
namespace {

// A node still to be built: which node, over which range of the per-axis orders.
struct PendingNode {
  uint32_t node;
  uint32_t begin;
  uint32_t end;
};

struct Split {
  int axis = -1;          // -1: no split position had a finite cost
  uint32_t position = 0;  // first entry of the right child in that axis's order
  double cost = std::numeric_limits<double>::infinity();  // sum of count * area over both sides
};

// NaN centroids sort last instead of breaking std::sort's ordering requirement.
float sortKey(float value) { return std::isnan(value) ? std::numeric_limits<float>::infinity() : value; }

class SweepBuilder {
 public:
  SweepBuilder(std::span<const Aabb> bounds, std::span<const glm::vec3> centroids, const BuildOptions& options)
      : bounds_(bounds), options_(options), goesLeft_(bounds.size()), scratch_(bounds.size()),
        rightAreas_(bounds.size()) {
    options_.maxLeafSize = std::max(options_.maxLeafSize, 1u);
    // Sorted once per axis; partitions below keep every node's range sorted on all axes.
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<uint32_t>& order = orders_[axis];
      order.resize(bounds.size());
      std::iota(order.begin(), order.end(), 0u);
      std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
        const float ka = sortKey(centroids[a][axis]), kb = sortKey(centroids[b][axis]);
        return ka < kb || (ka == kb && a < b);
      });
    }
  }

  Bvh build() {
    Bvh bvh;
    const auto count = static_cast<uint32_t>(bounds_.size());
    if (count == 0) return bvh;
    bvh.nodes.reserve(2 * size_t{count} - 1);
    bvh.nodes.push_back({});
    std::vector<PendingNode> pending{{HMB_BVH_ROOT, 0, count}};
    while (!pending.empty()) {
      const PendingNode item = pending.back();
      pending.pop_back();
      Node& node = bvh.nodes[item.node];
      const Aabb box = rangeBounds(item.begin, item.end);
      setBounds(node, box);
      const uint32_t n = item.end - item.begin;
      Split split = n > 1 ? bestSplit(item.begin, item.end) : Split{};
      if (n <= options_.maxLeafSize && !splitPays(split, box, n)) {
        node.leftOrFirst = item.begin;
        node.count = n;
        continue;
      }
      if (split.axis < 0) split = Split{0, item.begin + n / 2, 0.0};  // no finite cost: halve
      partition(item.begin, item.end, split);
      const auto left = static_cast<uint32_t>(bvh.nodes.size());
      node.leftOrFirst = left;  // written before the push_backs: `node` is a reference into nodes
      node.count = 0;
      bvh.nodes.push_back({});
      bvh.nodes.push_back({});
      pending.push_back({left + 1, split.position, item.end});
      pending.push_back({left, item.begin, split.position});
    }
    bvh.primitiveIndices = std::move(orders_[0]);
    return bvh;
  }

 private:
  Aabb rangeBounds(uint32_t begin, uint32_t end) const {
    Aabb box;
    for (uint32_t i = begin; i < end; ++i) box.grow(bounds_[orders_[0][i]]);
    return box;
  }

  // Costs compared multiplied by the parent's area, so that a zero-area parent gives no NaN.
  bool splitPays(const Split& split, const Aabb& box, uint32_t n) const {
    if (split.axis < 0) return false;
    const double area = box.surfaceArea();
    const double leafCost = double{options_.intersectionCost} * n * area;
    const double splitCost = double{options_.traversalCost} * area + double{options_.intersectionCost} * split.cost;
    return splitCost < leafCost;
  }

  Split bestSplit(uint32_t begin, uint32_t end) {
    Split best;
    const int64_t n = end - begin;
    const auto offCentre = [&](uint32_t position) { return std::abs(2 * int64_t{position - begin} - n); };
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<uint32_t>& order = orders_[axis];
      Aabb right;
      for (uint32_t i = end - 1; i > begin; --i) {
        right.grow(bounds_[order[i]]);
        rightAreas_[i - begin] = right.surfaceArea();
      }
      Aabb left;
      for (uint32_t i = begin + 1; i < end; ++i) {
        left.grow(bounds_[order[i - 1]]);
        const double cost =
            double{left.surfaceArea()} * (i - begin) + double{rightAreas_[i - begin]} * (end - i);
        if (!std::isfinite(cost)) continue;
        if (best.axis < 0 || cost < best.cost || (cost == best.cost && offCentre(i) < offCentre(best.position)))
          best = Split{axis, i, cost};
      }
    }
    return best;
  }

  // Splits the range at the chosen position of the chosen axis; the other axes' orders are
  // partitioned stably by the same sides, so they stay sorted.
  void partition(uint32_t begin, uint32_t end, const Split& split) {
    const std::vector<uint32_t>& chosen = orders_[split.axis];
    for (uint32_t i = begin; i < end; ++i) goesLeft_[chosen[i]] = i < split.position;
    for (int axis = 0; axis < 3; ++axis) {
      if (axis == split.axis) continue;
      std::vector<uint32_t>& order = orders_[axis];
      uint32_t leftEnd = begin, rightEnd = split.position;
      for (uint32_t i = begin; i < end; ++i) scratch_[goesLeft_[order[i]] ? leftEnd++ : rightEnd++] = order[i];
      std::copy(scratch_.begin() + begin, scratch_.begin() + end, order.begin() + begin);
    }
  }

  std::span<const Aabb> bounds_;
  BuildOptions options_;
  std::array<std::vector<uint32_t>, 3> orders_;
  std::vector<uint8_t> goesLeft_;
  std::vector<uint32_t> scratch_;
  std::vector<float> rightAreas_;
};

}  // namespace

Bvh buildReferenceSah(std::span<const Aabb> primitiveBounds, std::span<const glm::vec3> centroids,
                      const BuildOptions& options) {
  if (primitiveBounds.size() != centroids.size())
    throw std::invalid_argument("buildReferenceSah: primitiveBounds and centroids differ in size");
  if (primitiveBounds.size() > std::numeric_limits<uint32_t>::max() / 2)
    throw std::invalid_argument("buildReferenceSah: too many primitives for 32-bit node indices");
  return SweepBuilder(primitiveBounds, centroids, options).build();
}

}  // namespace hmb::bvh
