#include "runtime/passes/reference_sum_tree.h"

#include <algorithm>
#include <string>

#include "hmblur/error.h"

namespace hmb::passes {

SampleRange shardSamples(uint32_t samples, uint32_t index, uint32_t count) {
  if (count == 0 || index >= count) throw Error("shard " + std::to_string(index) + "/" + std::to_string(count) +
                                                ": the index must be below the count");
  if (count > samples)
    throw Error("shard count " + std::to_string(count) + " is more than the " + std::to_string(samples) +
                " samples per pixel: a shard would be empty");
  return {static_cast<uint32_t>(uint64_t(samples) * index / count),
          static_cast<uint32_t>(uint64_t(samples) * (index + 1) / count)};
}

bool SumNode::isLeftOf(const SumNode& right) const {
  return !isFirstSample() && !right.isFirstSample() && level == right.level && level < 32 &&
         ((start >> level) & 1) == 0 && leafEnd() == right.start;
}

std::vector<SumNode> heldNodes(SampleRange shard, uint32_t done) {
  std::vector<SumNode> stack;
  for (uint32_t sample = shard.begin; sample < shard.begin + done; ++sample) {
    SumNode node = SumNode::ofSample(sample);
    while (!stack.empty() && stack.back().isLeftOf(node)) {
      node = node.parent();
      stack.pop_back();
    }
    stack.push_back(node);
  }
  return stack;
}

SumStack::SumStack(SumSlots& slots) : slots_(slots) {
  if (slots.count() < 3) throw Error("reference sums: at least three slots are needed");
  for (uint32_t slot = slots.count(); slot-- > 0;) free_.push_back(slot);
}

uint32_t SumStack::freeSlot() {
  if (free_.empty()) {
    const auto deepest = std::find_if(stack_.begin(), stack_.end(), [](const Entry& e) { return e.slot.has_value(); });
    if (deepest == stack_.end()) throw Error("reference sums: no slot left to park");
    park(*deepest);
  }
  const uint32_t slot = free_.back();
  free_.pop_back();
  return slot;
}

void SumStack::flush() {
  if (pendingAdds_.empty()) return;
  slots_.add(pendingAdds_);
  pendingAdds_.clear();
}

void SumStack::park(Entry& entry) {
  flush();
  entry.parked = slots_.download(*entry.slot);
  free_.push_back(*entry.slot);
  entry.slot.reset();
}

uint32_t SumStack::onDevice(Entry& entry) {
  if (!entry.slot) {
    const uint32_t slot = freeSlot();
    flush();
    slots_.upload(slot, entry.parked);
    entry.parked = {};
    entry.slot = slot;
  }
  return *entry.slot;
}

SumStack::Entry SumStack::climb(Entry carry) {
  while (!stack_.empty() && stack_.back().node.isLeftOf(carry.node)) {
    const uint32_t left = onDevice(stack_.back());
    add(left, *carry.slot);
    free_.push_back(*carry.slot);
    carry = {carry.node.parent(), left, {}};
    stack_.pop_back();
  }
  return carry;
}

SumStack::SampleStep SumStack::beginSample(uint32_t sample) {
  if (pending_) throw Error("reference sums: a sample is already begun");
  SumNode node = SumNode::ofSample(sample);
  SampleStep step;
  // The nodes the sample completes that are on the device, nearest first, go to the kernel.
  for (size_t i = stack_.size(); i > 0 && step.fold.size() < kMaxKernelFolds; --i) {
    const Entry& left = stack_[i - 1];
    if (!left.node.isLeftOf(node) || !left.slot) break;
    step.fold.push_back(*left.slot);
    node = node.parent();
  }
  step.target = step.fold.empty() ? freeSlot() : step.fold.back();  // read before written, pixel by pixel
  pending_ = Entry{node, step.target, {}};
  pendingFolds_ = static_cast<uint32_t>(step.fold.size());
  flush();  // the kernel reads the slots next
  return step;
}

void SumStack::finishSample() {
  if (!pending_) throw Error("reference sums: no sample begun");
  for (uint32_t i = 0; i < pendingFolds_; ++i) {
    if (*stack_.back().slot != *pending_->slot) free_.push_back(*stack_.back().slot);
    stack_.pop_back();
  }
  Entry carry = climb(std::move(*pending_));
  pending_.reset();
  if (carry.node.isFirstSample()) {
    // Sample 0 is the one node that pixels the kernel leaves out hold a value in: it waits in
    // host memory, and its slot is cleared for the nodes to come.
    const uint32_t slot = *carry.slot;
    park(carry);
    slots_.clear(slot);
  }
  stack_.push_back(std::move(carry));
  flush();
}

void SumStack::push(const SumNode& node, std::vector<glm::vec4> sums, bool merge) {
  if (!merge) {
    stack_.push_back({node, std::nullopt, std::move(sums)});
    return;
  }
  Entry entry{node, std::nullopt, std::move(sums)};
  onDevice(entry);
  stack_.push_back(climb(std::move(entry)));
}

std::vector<SumNode> SumStack::nodes() const {
  std::vector<SumNode> nodes;
  for (const Entry& e : stack_) nodes.push_back(e.node);
  return nodes;
}

std::vector<glm::vec4> SumStack::sumsOf(size_t index) const {
  const Entry& e = stack_.at(index);
  return e.slot ? slots_.download(*e.slot) : e.parked;
}

uint32_t SumStack::total() {
  if (stack_.empty()) throw Error("reference: no samples to add up");
  // Sample 0's sums go to the device first, so that every addition below goes in one pass.
  std::optional<uint32_t> first;
  if (stack_.front().node.isFirstSample()) {
    first = onDevice(stack_.front());
    stack_.erase(stack_.begin());
  }
  // ((B1 + B2) + B3) + ..., each node taken off the bottom of the stack.
  std::optional<uint32_t> sum;
  while (!stack_.empty()) {
    Entry next = std::move(stack_.front());
    stack_.erase(stack_.begin());
    const uint32_t slot = onDevice(next);
    if (!sum) {
      sum = slot;
      continue;
    }
    add(*sum, slot);
    free_.push_back(slot);
  }
  if (first && sum) {
    add(*first, *sum);
    free_.push_back(*sum);
  }
  flush();
  return first ? *first : *sum;
}

}  // namespace hmb::passes
