#include "runtime/passes/reference_sum_tree.h"

#include <algorithm>
#include <bit>
#include <functional>
#include <map>
#include <set>

#include "hmblur/error.h"

namespace hmb::passes {

std::string SumNode::text() const {
  if (isFirstSample()) return "sample 0";
  // Leaf l is sample l + 1.
  return "samples " + std::to_string(uint64_t(start) + 1) + ".." + std::to_string(leafEnd());
}

SampleRange shardSamples(uint32_t samples, uint32_t index, uint32_t count) {
  if (count == 0 || index >= count) throw Error("shard " + std::to_string(index) + "/" + std::to_string(count) +
                                                ": the index must be below the count");
  if (count > samples)
    throw Error("shard count " + std::to_string(count) + " is more than the " + std::to_string(samples) +
                " samples per pixel: a shard would be empty");
  return {static_cast<uint32_t>(uint64_t(samples) * index / count),
          static_cast<uint32_t>(uint64_t(samples) * (index + 1) / count)};
}

ShardSumTree::ShardSumTree(uint32_t samples, SampleRange shard)
    : samples_(samples),
      shard_(shard),
      levels_(samples > 1 ? static_cast<uint32_t>(std::bit_width(samples - 1)) : 0u),
      next_(shard.begin) {
  if (shard.begin > shard.end || shard.end > samples) throw Error("shard samples out of the render's range");
  slots_.resize(slotCount());
}

SumStep ShardSumTree::add() {
  if (finished()) throw Error("the shard's samples are all taken");
  const uint32_t sample = next_++;
  if (sample == 0) {
    slots_[0] = SumNode::firstSample();
    return {0, 0, 0};
  }
  const uint64_t leaf = sample - 1;
  const uint64_t firstLeaf = shard_.begin > 0 ? shard_.begin - 1 : 0;
  // Climb while the node ending at this leaf is a right half whose left half lies in the shard
  // (it waits, whole, in the right slot of its level).
  uint32_t level = 0;
  bool leftOutside = false;
  for (;; ++level) {
    const uint64_t size = uint64_t(1) << level;
    const uint64_t start = leaf + 1 - size;
    if (((start >> level) & 1) == 0) break;  // a left half: it waits for its right one
    if (start < firstLeaf + size) {           // its left half starts before the shard
      leftOutside = true;
      break;
    }
    const SumNode left{level, static_cast<uint32_t>(start - size)};
    if (slots_[rightSlot(level)] != left) throw Error("reference sum tree: " + left.text() + " is not held");
    slots_[rightSlot(level)].reset();
  }
  const SumNode node{level, static_cast<uint32_t>(leaf + 1 - (uint64_t(1) << level))};
  const uint32_t target = leftOutside ? leftSlot(level) : rightSlot(level);
  slots_.at(target) = node;
  return {rightSlot(0), level, target};
}

std::vector<ShardSumTree::Held> ShardSumTree::held() const {
  std::vector<Held> nodes;
  for (uint32_t slot = 0; slot < slots_.size(); ++slot)
    if (slots_[slot]) nodes.push_back({slot, *slots_[slot]});
  return nodes;
}

namespace {

// Evaluates the tree in post order, handing out slots as it goes.
class FoldBuilder {
 public:
  FoldBuilder(uint32_t samples, const std::vector<ShardSumTree::Held>& resident, const std::vector<SumNode>& loaded,
              uint32_t firstFreeSlot)
      : leaves_(samples > 0 ? samples - 1 : 0), nextSlot_(firstFreeSlot) {
    for (const ShardSumTree::Held& h : resident) {
      add(h.node, h.slot);
      nextSlot_ = std::max(nextSlot_, h.slot + 1);
    }
    for (const SumNode& node : loaded) add(node, std::nullopt);
    program_.slotCount = nextSlot_;
    // Disjoint: sorted by start, each begins where the one before ends or later.
    uint64_t end = 0;
    const SumNode* before = nullptr;
    for (const auto& [start, node] : byStart_) {
      if (start < end) throw Error("reference parts overlap: " + before->text() + " and " + node.text());
      end = node.leafEnd();
      before = &node;
    }
  }

  FoldProgram build() {
    std::optional<uint32_t> total;
    uint64_t start = 0;
    for (int level = 31; level >= 0; --level) {
      if (((leaves_ >> level) & 1) == 0) continue;
      total = combine(total, eval({static_cast<uint32_t>(level), static_cast<uint32_t>(start)}));
      start += uint64_t(1) << level;
    }
    program_.result = combine(take(SumNode::firstSample()), total);
    return std::move(program_);
  }

 private:
  void add(const SumNode& node, std::optional<uint32_t> slot) {
    if (!node.isFirstSample()) {
      if (node.level >= 32 || node.start % (uint64_t(1) << node.level) != 0 || node.leafEnd() > leaves_)
        throw Error("reference part holds " + node.text() + ", not a node of the sum tree of " +
                    std::to_string(uint64_t(leaves_) + 1) + " samples");
      byStart_.emplace(node.start, node);
    }
    if (!present_.emplace(node, slot).second) throw Error("reference parts both hold " + node.text());
  }

  // The slot holding `node`'s sum, loaded if it is not resident; none when no part has it.
  std::optional<uint32_t> take(const SumNode& node) {
    const auto found = present_.find(node);
    if (found == present_.end()) return std::nullopt;
    if (found->second) return found->second;
    const uint32_t slot = freeSlot();
    program_.steps.push_back({FoldStep::Kind::Load, node, slot, 0});
    return slot;
  }

  std::optional<uint32_t> eval(const SumNode& node) {
    if (const std::optional<uint32_t> slot = take(node)) return slot;
    // Nothing inside it is held: it is left out.
    const auto inside = byStart_.lower_bound(node.start);
    if (node.level == 0 || inside == byStart_.end() || inside->first >= node.leafEnd()) return std::nullopt;
    const uint32_t half = node.start + (1u << (node.level - 1));
    const std::optional<uint32_t> left = eval({node.level - 1, node.start});
    return combine(left, eval({node.level - 1, half}));
  }

  std::optional<uint32_t> combine(std::optional<uint32_t> left, std::optional<uint32_t> right) {
    if (!left) return right;
    if (!right) return left;
    program_.steps.push_back({FoldStep::Kind::Add, {}, *left, *right});
    free_.insert(*right);
    return left;
  }

  uint32_t freeSlot() {
    if (!free_.empty()) {
      const uint32_t slot = *free_.begin();
      free_.erase(free_.begin());
      return slot;
    }
    program_.slotCount = std::max(program_.slotCount, nextSlot_ + 1);
    return nextSlot_++;
  }

  uint32_t leaves_;
  uint32_t nextSlot_;
  std::map<SumNode, std::optional<uint32_t>> present_;  // node -> its resident slot
  std::multimap<uint32_t, SumNode> byStart_;            // the tree's nodes by first leaf
  std::set<uint32_t> free_;
  FoldProgram program_;
};

}  // namespace

FoldProgram foldProgram(uint32_t samples, const std::vector<ShardSumTree::Held>& resident,
                        const std::vector<SumNode>& loaded, uint32_t firstFreeSlot) {
  return FoldBuilder(samples, resident, loaded, firstFreeSlot).build();
}

}  // namespace hmb::passes
