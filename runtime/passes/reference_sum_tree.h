// The order in which the reference adds up a pixel's samples. It is fixed by the sample indices
// alone, so that the samples of one render split into shards (runs of consecutive indices,
// rendered on any machine, in any order) merge to the bits a single render gives.
//
// Sample 0 is held apart (a pixel that nothing moving crosses takes only it). Samples 1..N-1 are
// the leaves 0..N-2 of a tree of pairwise sums: a node is an aligned block of 2^level leaves and
// its sum is its left half's plus its right half's. The total is
//   sample 0 + (((B1 + B2) + B3) + ...),
// B1, B2, ... the largest aligned blocks that tile the leaves from the left (one per set bit of
// N - 1). A shard holds the largest tree nodes inside its run, at most two per level; the merge
// rebuilds every other node from them. Pairwise sums also keep the rounding error growing with
// log N rather than N.
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace hmb::passes {

// A node of the tree: leaves [start, start + 2^level), or sample 0.
struct SumNode {
  static constexpr uint32_t kFirstSample = 0xffffffffu;  // the level of the node holding sample 0
  uint32_t level = 0;
  uint32_t start = 0;

  static SumNode firstSample() { return {kFirstSample, 0}; }
  bool isFirstSample() const { return level == kFirstSample; }
  uint64_t leafEnd() const { return uint64_t(start) + (uint64_t(1) << level); }
  std::string text() const;  // "sample 0" or "samples 5..8"
  auto operator<=>(const SumNode&) const = default;
};

// Samples [begin, end) of a render.
struct SampleRange {
  uint32_t begin = 0;
  uint32_t end = 0;
  uint32_t size() const { return end - begin; }
};

// Shard `index` (0-based) of `count`: the count runs of consecutive samples, as even as they go.
SampleRange shardSamples(uint32_t samples, uint32_t index, uint32_t count);

// What the accumulate kernel does with one sample: it adds the sums in slots foldSlot ..
// foldSlot + foldLevels - 1 in turn before it (each the left neighbour of what it has so far)
// and writes the result to targetSlot.
struct SumStep {
  uint32_t foldSlot = 0;
  uint32_t foldLevels = 0;
  uint32_t targetSlot = 0;
};

// The nodes a shard's render holds on the device as it takes its samples in order, each in a
// slot: slot 0 holds sample 0; slot 1 + j the node of level j still waiting for its right
// neighbour; slot 1 + levels + j the node of level j whose left neighbour lies before the shard
// (only a shard that does not start at sample 0 has such nodes).
class ShardSumTree {
 public:
  // `samples`: the render's N; `shard` within [0, N).
  ShardSumTree(uint32_t samples, SampleRange shard);

  uint32_t slotCount() const { return 1 + levels_ * (shard_.begin > 1 ? 2 : 1); }
  uint32_t samplesDone() const { return next_ - shard_.begin; }
  bool finished() const { return next_ == shard_.end; }
  // The next sample's step; records that it was taken.
  SumStep add();
  // What the slots hold now, in slot order.
  struct Held {
    uint32_t slot;
    SumNode node;
  };
  std::vector<Held> held() const;

 private:
  uint32_t rightSlot(uint32_t level) const { return 1 + level; }
  uint32_t leftSlot(uint32_t level) const { return 1 + levels_ + level; }

  uint32_t samples_;
  SampleRange shard_;
  uint32_t levels_;  // levels of the tree over N - 1 leaves
  uint32_t next_;
  std::vector<std::optional<SumNode>> slots_;
};

// How to add up a set of nodes (disjoint, each a node of the tree of N samples) in the tree's
// order: loads of nodes into slots and sums of two slots into the left one's. Nodes already in
// a slot are read there; the others are loaded into free slots when they are needed, so that at
// most about one slot per level is in use however many nodes there are.
struct FoldStep {
  enum class Kind { Load, Add } kind;
  SumNode node;   // Load: the node to load into `left`
  uint32_t left;  // Add: left = left + right
  uint32_t right;
};

struct FoldProgram {
  std::vector<FoldStep> steps;
  std::optional<uint32_t> result;  // the slot holding the total; none when no node is given
  uint32_t slotCount = 0;          // slots the program uses (resident ones included)
};

// `resident`: nodes already in slots (their data may be overwritten); `loaded`: nodes to load.
// Throws hmb::Error when a node is not one of the tree's or two overlap.
FoldProgram foldProgram(uint32_t samples, const std::vector<ShardSumTree::Held>& resident,
                        const std::vector<SumNode>& loaded, uint32_t firstFreeSlot);

}  // namespace hmb::passes
