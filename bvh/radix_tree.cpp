#include "bvh/radix_tree.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "kernels/bvh/linear_bvh_layout.h"
#include "kernels/bvh/treelet_build_layout.h"

namespace hmb::bvh {

std::vector<glm::uvec2> radixTree(std::span<const uint32_t> codes) {
  const int n = static_cast<int>(codes.size());
  const auto sharedBits = [&](int i, int j) {
    if (j < 0 || j >= n) return -1;
    if (codes[i] != codes[j]) return std::countl_zero(codes[i] ^ codes[j]);
    return 32 + std::countl_zero(uint32_t(i ^ j));
  };
  std::vector<glm::uvec2> children(n > 1 ? n - 1 : 0);
  for (int i = 0; i + 1 < n; ++i) {
    const int d = sharedBits(i, i + 1) > sharedBits(i, i - 1) ? 1 : -1;
    const int least = sharedBits(i, i - d);
    int reach = 2;
    while (sharedBits(i, i + reach * d) > least) reach *= 2;
    int length = 0;
    for (int step = reach / 2; step >= 1; step /= 2)
      if (sharedBits(i, i + (length + step) * d) > least) length += step;
    const int j = i + length * d, rangeBits = sharedBits(i, j);
    int split = 0;
    for (int step = (length + 1) / 2;; step = (step + 1) / 2) {
      if (sharedBits(i, i + (split + step) * d) > rangeBits) split += step;
      if (step == 1) break;
    }
    const int gamma = i + split * d + std::min(d, 0);
    const uint32_t leaves = uint32_t(n - 1);
    children[i] = {std::min(i, j) == gamma ? leaves + gamma : uint32_t(gamma),
                   std::max(i, j) == gamma + 1 ? leaves + gamma + 1 : uint32_t(gamma + 1)};
  }
  return children;
}

namespace {

glm::vec3 centroidOf(const Aabb& box) {
  const glm::vec3 c = 0.5f * (box.min + box.max);
  const bool finite = std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z);
  return glm::all(glm::lessThanEqual(box.min, box.max)) && finite ? c : glm::vec3(0.0f);
}

// As treelet_common.glsl's halfArea (this file is compiled without fused multiply-adds).
float halfArea(const glm::vec3& lo, const glm::vec3& hi) {
  const glm::vec3 e = glm::max(hi - lo, glm::vec3(0.0f));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

// A subtree as treelet_optimize.comp holds it.
struct Subtree {
  glm::vec3 lo{0.0f}, hi{0.0f};
  float cost = 0.0f;
  uint32_t count = 0, below = 0, height = 0, id = 0;
};

struct Node {
  Subtree s;
  uint32_t left = 0, right = 0;
};

class TreeletTree {
 public:
  TreeletTree(uint32_t n, uint32_t maxLeaf) : n_(n), maxLeaf_(maxLeaf), nodes_(2 * size_t(n)) {}
  Node& at(uint32_t node) { return nodes_.at(node); }
  Subtree load(uint32_t node) {
    Subtree s = nodes_.at(node).s;
    s.id = node;
    return s;
  }
  void merge(Subtree& a, const Subtree& b) const {
    a.lo = glm::min(a.lo, b.lo);
    a.hi = glm::max(a.hi, b.hi);
    const float area = halfArea(a.lo, a.hi);
    const float split = area + a.cost + b.cost;
    a.count += b.count;
    const float asLeaf = a.count <= maxLeaf_ ? area * float(a.count) : std::numeric_limits<float>::infinity();
    if (asLeaf <= split) {
      a.cost = asLeaf;
      a.below = 0;
      a.height = 1;
    } else {
      a.cost = split;
      a.below = 2 + a.below + b.below;
      a.height = 1 + std::max(a.height, b.height);
    }
  }
  void store(const Subtree& s, uint32_t node, uint32_t left, uint32_t right) {
    Node& out = nodes_.at(node);
    const uint32_t id = out.s.id;
    out.s = s;
    out.s.id = id;
    out.left = left;
    out.right = right;
  }
  void finish(uint32_t p) {
    constexpr uint32_t kLeaves = HMB_TREELET_LEAVES;
    const uint32_t left = at(p).left, right = at(p).right;
    Subtree built = load(left);
    merge(built, load(right));
    store(built, p, left, right);
    if (built.count < 3) return;

    std::vector<Subtree> slots{load(left), load(right)};
    std::vector<uint32_t> interior{p};
    while (slots.size() < kLeaves) {
      uint32_t widest = kLeaves;
      float widestArea = -1.0f;
      for (uint32_t s = 0; s < slots.size(); ++s) {
        const float area = halfArea(slots[s].lo, slots[s].hi);
        if (slots[s].id < n_ && area > widestArea) {
          widest = s;
          widestArea = area;
        }
      }
      if (widest == kLeaves) break;
      const uint32_t opened = slots[widest].id;
      interior.push_back(opened);
      slots[widest] = load(at(opened).left);
      slots.push_back(load(at(opened).right));
    }
    const uint32_t leaves = static_cast<uint32_t>(slots.size());
    std::vector<glm::uvec2> merges;
    std::vector<uint32_t> mergedInto;
    std::vector<uint32_t> slotIds;
    for (const Subtree& s : slots) slotIds.push_back(s.id);
    uint32_t live = leaves;
    for (uint32_t m = 0; m + 1 < leaves; ++m) {
      uint32_t bestA = 0, bestB = 1;
      float bestArea = std::numeric_limits<float>::infinity();
      for (uint32_t a = 0; a + 1 < live; ++a)
        for (uint32_t b = a + 1; b < live; ++b) {
          const float area = halfArea(glm::min(slots[a].lo, slots[b].lo), glm::max(slots[a].hi, slots[b].hi));
          if (area < bestArea) {
            bestArea = area;
            bestA = a;
            bestB = b;
          }
        }
      const uint32_t node = m + 2 == leaves ? p : interior.at(m + 1);
      merges.push_back({slotIds[bestA], slotIds[bestB]});
      merge(slots[bestA], slots[bestB]);
      slotIds[bestA] = node;
      --live;
      slots[bestB] = slots[live];
      slotIds[bestB] = slotIds[live];
      mergedInto.push_back(node);
    }
    if (!(slots[0].cost < built.cost) || slots[0].height > built.height) return;
    for (uint32_t m = 0; m + 1 < leaves; ++m) {
      Subtree s = load(merges[m].x);
      merge(s, load(merges[m].y));
      store(s, mergedInto[m], merges[m].x, merges[m].y);
    }
  }

 private:
  uint32_t n_, maxLeaf_;
  std::vector<Node> nodes_;
};

}  // namespace

std::vector<uint32_t> treeletMortonCodes(std::span<const Aabb> boxes) {
  glm::vec3 low(std::numeric_limits<float>::infinity()), high = -low;
  for (const Aabb& box : boxes) {
    low = glm::min(low, centroidOf(box));
    high = glm::max(high, centroidOf(box));
  }
  const glm::vec3 extent = high - low;
  std::vector<uint32_t> codes;
  codes.reserve(boxes.size());
  for (const Aabb& box : boxes) {
    const glm::vec3 c = centroidOf(box);
    glm::uvec3 cell(0u);
    for (int a = 0; a < 3; ++a)
      if (extent[a] > 0.0f) cell[a] = uint32_t(std::clamp((c[a] - low[a]) * (1024.0f / extent[a]), 0.0f, 1023.0f));
    codes.push_back(gpu::mortonCode(cell));
  }
  return codes;
}

glm::uvec3 mortonCell(uint32_t code) {
  glm::uvec3 cell(0u);
  for (uint32_t bit = 0; bit < 10; ++bit) {
    cell.x |= ((code >> (3 * bit + 2)) & 1u) << bit;
    cell.y |= ((code >> (3 * bit + 1)) & 1u) << bit;
    cell.z |= ((code >> (3 * bit)) & 1u) << bit;
  }
  return cell;
}

Bvh buildTreeletTree(std::span<const Aabb> boxes, std::span<const uint32_t> codes,
                     std::span<const uint32_t> primitives, uint32_t maxLeaf) {
  if (codes.size() != boxes.size() || primitives.size() != boxes.size())
    throw std::invalid_argument("buildTreeletTree: a code and a primitive for each box");
  const auto n = static_cast<uint32_t>(boxes.size());
  Bvh out;
  if (n == 0) return out;
  TreeletTree tree(n, maxLeaf);
  for (uint32_t k = 0; k < n; ++k) {
    const Aabb& box = boxes[primitives[k]];
    Subtree& s = tree.at(n + k).s;
    s.lo = box.min;
    s.hi = box.max;
    s.cost = glm::all(glm::lessThanEqual(box.min, box.max)) ? halfArea(box.min, box.max) : 0.0f;
    s.count = 1;
    s.below = 0;
    s.height = 1;
  }
  // The radix tree in the kernels' names (interior p, leaf n + p), finished children first.
  const std::vector<glm::uvec2> children = radixTree(codes);
  const auto deviceName = [&](uint32_t karras) { return karras >= n - 1 ? n + (karras - (n - 1)) : karras; };
  for (uint32_t i = 0; i + 1 < n; ++i) {
    tree.at(i).left = deviceName(children[i].x);
    tree.at(i).right = deviceName(children[i].y);
  }
  const uint32_t root = n == 1 ? n : 0u;
  std::vector<std::pair<uint32_t, bool>> stack{{root, false}};
  while (!stack.empty()) {
    const auto [node, expanded] = stack.back();
    stack.pop_back();
    if (node >= n) continue;
    if (expanded) {
      tree.finish(node);
      continue;
    }
    stack.push_back({node, true});
    stack.push_back({tree.at(node).left, false});
    stack.push_back({tree.at(node).right, false});
  }

  // Laid out: (node, its place, where its children go, its first primitive's place).
  out.nodes.resize(1 + tree.at(root).s.below);
  out.primitiveIndices.resize(n);
  struct Place {
    uint32_t node, at, base, first;
  };
  std::vector<Place> places{{root, 0u, 1u, 0u}};
  while (!places.empty()) {
    const Place p = places.back();
    places.pop_back();
    const Subtree& s = tree.at(p.node).s;
    bvh::Node& node = out.nodes.at(p.at);
    setBounds(node, Aabb{s.lo, s.hi});
    if (s.below == 0) {
      node.leftOrFirst = p.first;
      node.count = s.count;
      // Its primitives in the order of its leaves, left first.
      std::vector<std::pair<uint32_t, uint32_t>> leaves{{p.node, p.first}};
      while (!leaves.empty()) {
        const auto [at, first] = leaves.back();
        leaves.pop_back();
        if (at >= n) {
          out.primitiveIndices.at(first) = primitives[at - n];
          continue;
        }
        leaves.push_back({tree.at(at).left, first});
        leaves.push_back({tree.at(at).right, first + tree.at(tree.at(at).left).s.count});
      }
      continue;
    }
    node.leftOrFirst = p.base;
    node.count = 0;
    const uint32_t left = tree.at(p.node).left, right = tree.at(p.node).right;
    const Subtree& l = tree.at(left).s;
    places.push_back({left, p.base, p.base + 2, p.first});
    places.push_back({right, p.base + 1, p.base + 2 + l.below, p.first + l.count});
  }
  return out;
}

Bvh buildTreeletReference(std::span<const Aabb> boxes, uint32_t maxLeaf) {
  const std::vector<uint32_t> codes = treeletMortonCodes(boxes);
  std::vector<uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return codes[a] < codes[b]; });
  std::vector<uint32_t> sorted;
  for (const uint32_t i : order) sorted.push_back(codes[i]);
  return buildTreeletTree(boxes, sorted, order, maxLeaf);
}

}  // namespace hmb::bvh
