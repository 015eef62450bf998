// The order in which the reference adds up a pixel's samples. It is fixed by the sample indices
// alone, so that the samples of one render split into shards (runs of consecutive indices,
// rendered on any machine, in any order) merge to the bits a single render gives.
//
// Sample 0 is held apart (a pixel that nothing moving crosses takes only it). Samples 1..N-1 are
// the leaves 0..N-2 of a tree of pairwise sums: a node is an aligned block of 2^level leaves and
// its sum is its left half's plus its right half's. The total is
//   sample 0 + (((B1 + B2) + B3) + ...),
// B1, B2, ... the largest aligned blocks that tile the leaves from the left (one per set bit of
// N - 1). Pairwise sums also keep the rounding error growing with log N rather than N.
//
// A SumStack keeps the nodes summed so far, in sample order: a new node is added to the nodes
// it completes (its left neighbours of the same size) as it arrives. A render pushes its
// samples, a merge the nodes its parts hold, and both end with the same additions. Every
// addition is the device's (SumSlots), so a merge and a render on one device agree to the bit;
// the stack keeps at most a few nodes on the device and parks the others in host memory.
#pragma once

#include <compare>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

namespace hmb::passes {

// A node of the tree: leaves [start, start + 2^level), or sample 0.
struct SumNode {
  static constexpr uint32_t kFirstSample = 0xffffffffu;  // the level of the node holding sample 0
  uint32_t level = 0;
  uint32_t start = 0;

  static SumNode firstSample() { return {kFirstSample, 0}; }
  static SumNode ofSample(uint32_t sample) { return sample == 0 ? firstSample() : SumNode{0, sample - 1}; }
  bool isFirstSample() const { return level == kFirstSample; }
  // The first sample it holds (leaf l is sample l + 1): a stack takes nodes in this order.
  uint64_t firstSampleIndex() const { return isFirstSample() ? 0 : uint64_t(start) + 1; }
  uint64_t leafEnd() const { return uint64_t(start) + (uint64_t(1) << level); }
  // Whether this is the left half of the node whose right half is `right`.
  bool isLeftOf(const SumNode& right) const;
  SumNode parent() const { return {level + 1, static_cast<uint32_t>(start & ~((uint64_t(2) << level) - 1))}; }
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

// The nodes a shard holds after its first `done` samples, in sample order.
std::vector<SumNode> heldNodes(SampleRange shard, uint32_t done);

// The device's sums: `count()` slots of a vec4 a pixel (rgb sum, w the number of samples).
class SumSlots {
 public:
  virtual ~SumSlots() = default;
  virtual uint32_t count() const = 0;
  virtual void upload(uint32_t slot, std::span<const glm::vec4> sums) = 0;
  virtual std::vector<glm::vec4> download(uint32_t slot) = 0;
  virtual void clear(uint32_t slot) = 0;
  // For each pair in turn, slot x = slot x + slot y (x the left node).
  virtual void add(std::span<const glm::uvec2> pairs) = 0;
};

class SumStack {
 public:
  static constexpr uint32_t kMaxKernelFolds = 8;  // nodes the accumulate kernel adds in place

  // At least three slots.
  explicit SumStack(SumSlots& slots);

  // A sample of a render, in order: the accumulate kernel adds the sums in `fold` (slots,
  // nearest node first) before the sample's value, each as the left operand, and writes the
  // result to `target`; call finishSample() once it has run. A pixel the kernel leaves out
  // holds zero in every node but sample 0's.
  struct SampleStep {
    std::vector<uint32_t> fold;
    uint32_t target = 0;
  };
  SampleStep beginSample(uint32_t sample);
  void finishSample();

  // A node whose sums are known: a part's, added to the nodes it completes (`merge`), or a
  // checkpoint's own, held as it is.
  void push(const SumNode& node, std::vector<glm::vec4> sums, bool merge);

  std::vector<SumNode> nodes() const;                // held, in sample order
  std::vector<glm::vec4> sumsOf(size_t index) const;  // of nodes()[index]; after a flush
  // Adds every held node up in the tree's order; the slot holding the total. The stack is
  // empty after it. Throws when nothing is held.
  uint32_t total();

 private:
  struct Entry {
    SumNode node;
    std::optional<uint32_t> slot;    // on the device, or
    std::vector<glm::vec4> parked;   // in host memory
  };
  uint32_t freeSlot();  // parks the deepest node on the device when every slot is taken
  uint32_t onDevice(Entry& entry);
  void park(Entry& entry);
  // Adds `carry` (on the device) to every held node it completes; returns it with the result.
  Entry climb(Entry carry);
  // Additions wait here and go to the device together, before anything else reads the slots.
  void add(uint32_t left, uint32_t right) { pendingAdds_.emplace_back(left, right); }
  void flush();

  SumSlots& slots_;
  std::vector<Entry> stack_;
  std::vector<uint32_t> free_;
  std::optional<Entry> pending_;  // the sample between beginSample and finishSample
  uint32_t pendingFolds_ = 0;
  std::vector<glm::uvec2> pendingAdds_;
};

}  // namespace hmb::passes
