// The reference's order of summation (runtime/passes/reference_sum_tree.h) against its
// definition, on the host: what accumulate_sample and fold_sums do to one pixel, played in plain
// C++ with the slots the tree hands out, gives the definition's total bit for bit, for a whole
// render and for every split into shards merged in any order.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/passes/reference_sum_tree.h"
#include "tests/support/expect_error.h"

namespace hmb::test {
namespace {

using passes::SampleRange;
using passes::SumNode;
using passes::SumSlots;
using passes::SumStack;

// The definition: sample 0 + (((B1 + B2) + B3) + ...), each block the sum of its halves.
float blockSum(const std::vector<float>& samples, uint32_t level, uint64_t start) {
  if (level == 0) return samples[start + 1];
  const uint64_t half = uint64_t(1) << (level - 1);
  return blockSum(samples, level - 1, start) + blockSum(samples, level - 1, start + half);
}

float definedTotal(const std::vector<float>& samples) {
  const uint64_t leaves = samples.size() - 1;
  if (leaves == 0) return samples[0];
  float total = 0.0f;
  bool any = false;
  uint64_t start = 0;
  for (int level = 63; level >= 0; --level) {
    if (((leaves >> level) & 1) == 0) continue;
    const float block = blockSum(samples, static_cast<uint32_t>(level), start);
    total = any ? total + block : block;
    any = true;
    start += uint64_t(1) << level;
  }
  return samples[0] + total;
}

// The device's slots in host memory, each pixel's sums added as fold_sums adds them. A slot no
// one wrote holds NaN, which would reach a total that read it.
class HostSlots final : public SumSlots {
 public:
  HostSlots(uint32_t count, size_t pixels, float fill)
      : data_(count, std::vector<glm::vec4>(pixels, glm::vec4(fill))) {}
  uint32_t count() const override { return static_cast<uint32_t>(data_.size()); }
  void upload(uint32_t slot, std::span<const glm::vec4> sums) override {
    ASSERT_EQ(sums.size(), data_.at(slot).size());
    std::copy(sums.begin(), sums.end(), data_.at(slot).begin());
    ++uploads;
  }
  std::vector<glm::vec4> download(uint32_t slot) override {
    ++downloads;
    return data_.at(slot);
  }
  void clear(uint32_t slot) override { std::fill(data_.at(slot).begin(), data_.at(slot).end(), glm::vec4(0.0f)); }
  void add(std::span<const glm::uvec2> pairs) override {
    for (const glm::uvec2& p : pairs)
      for (size_t i = 0; i < data_[p.x].size(); ++i) data_.at(p.x)[i] = data_[p.x][i] + data_.at(p.y)[i];
  }
  std::vector<glm::vec4>& operator[](uint32_t slot) { return data_.at(slot); }

  size_t uploads = 0, downloads = 0;

 private:
  std::vector<std::vector<glm::vec4>> data_;
};

// Pixel 0 takes every sample; pixel 1 only sample 0, as a pixel nothing moving crosses.
constexpr size_t kPixels = 2;

struct Part {
  uint32_t done = 0;  // samples taken
  std::vector<SumNode> nodes;
  std::vector<std::vector<glm::vec4>> sums;
};

// A render of the shard's samples as the stage runs it, the accumulate kernel played per pixel,
// from a part when given and for at most `stopAfter` samples: its part, its total, and how
// many nodes it parked in host memory on the way.
struct Rendered {
  Part part;
  std::vector<glm::vec4> total;
  size_t parked = 0;
};

Rendered renderShard(const std::vector<float>& samples, SampleRange shard, uint32_t slotCount,
                     const Part* resumeFrom = nullptr, uint32_t stopAfter = ~0u) {
  HostSlots slots(slotCount, kPixels, 0.0f);
  SumStack stack(slots);
  uint32_t done = 0;
  if (resumeFrom) {
    for (size_t i = 0; i < resumeFrom->nodes.size(); ++i) stack.push(resumeFrom->nodes[i], resumeFrom->sums[i], false);
    done = resumeFrom->done;
  }
  for (uint32_t s = shard.begin + done; s < shard.end && done < stopAfter; ++s, ++done) {
    const SumStack::SampleStep step = stack.beginSample(s);
    EXPECT_LE(step.fold.size(), SumStack::kMaxKernelFolds);
    for (size_t p = 0; p < kPixels; ++p) {
      if (s > 0 && p == 1) continue;  // left out by the kernel
      glm::vec4 node(samples[s], 0.0f, 0.0f, 1.0f);
      for (const uint32_t f : step.fold) node = slots[f][p] + node;
      slots[step.target][p] = node;
    }
    stack.finishSample();
    EXPECT_EQ(stack.nodes(), passes::heldNodes(shard, done + 1));
  }
  Rendered rendered;
  rendered.parked = slots.downloads;
  rendered.part.done = done;
  rendered.part.nodes = stack.nodes();
  for (size_t i = 0; i < rendered.part.nodes.size(); ++i) rendered.part.sums.push_back(stack.sumsOf(i));
  rendered.total = slots[stack.total()];
  return rendered;
}

std::vector<glm::vec4> mergeParts(const std::vector<Part>& parts, uint32_t slotCount) {
  HostSlots slots(slotCount, kPixels, std::numeric_limits<float>::quiet_NaN());
  SumStack stack(slots);
  std::vector<std::pair<SumNode, const std::vector<glm::vec4>*>> nodes;
  for (const Part& part : parts)
    for (size_t i = 0; i < part.nodes.size(); ++i) nodes.emplace_back(part.nodes[i], &part.sums[i]);
  std::sort(nodes.begin(), nodes.end(),
            [](const auto& a, const auto& b) { return a.first.firstSampleIndex() < b.first.firstSampleIndex(); });
  for (const auto& [node, sums] : nodes) stack.push(node, *sums, true);
  return slots[stack.total()];
}

uint32_t bitsOf(const glm::vec4& v) { return std::bit_cast<uint32_t>(v.x); }

// Whether `node` is a node of the tree of `samples` samples: aligned, within the N - 1 leaves.
bool isTreeNode(const SumNode& node, uint32_t samples) {
  if (node.isFirstSample()) return samples > 0;
  return node.level < 32 && node.start % (uint64_t(1) << node.level) == 0 && samples > 0 &&
         node.leafEnd() <= samples - 1;
}

// "sample 0" or "samples 5..8".
std::string text(const SumNode& node) {
  if (node.isFirstSample()) return "sample 0";
  return "samples " + std::to_string(node.firstSampleIndex()) + ".." + std::to_string(node.leafEnd());
}

// Values whose sums round at every step, over many magnitudes, with zeros among them.
std::vector<float> samplesOf(uint32_t n, std::mt19937& random) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::uniform_real_distribution<float> exponent(-12.0f, 12.0f);
  std::vector<float> samples(n);
  for (float& s : samples) {
    const float r = unit(random);
    s = r < 0.1f ? 0.0f : r < 0.5f ? unit(random) : std::exp2(exponent(random)) * (unit(random) + 0.5f);
  }
  return samples;
}

TEST(ReferenceSumTreeTest, ShardsAreConsecutiveRunsThatCoverTheSamples) {
  for (const uint32_t n : {1u, 2u, 7u, 16u, 255u, 256u, 1000u})
    for (const uint32_t k : {1u, 2u, 3u, 7u, 16u})
      if (k <= n) {
        uint32_t next = 0;
        for (uint32_t i = 0; i < k; ++i) {
          const SampleRange shard = passes::shardSamples(n, i, k);
          EXPECT_EQ(shard.begin, next) << n << " " << i << "/" << k;
          EXPECT_GT(shard.size(), 0u);
          EXPECT_LE(shard.size(), n / k + 1);
          next = shard.end;
        }
        EXPECT_EQ(next, n);
      }
  expectError([] { passes::shardSamples(4, 0, 5); }, "more than the 4 samples");
  expectError([] { passes::shardSamples(16, 3, 3); }, "below the count");
  expectError([] { passes::shardSamples(16, 0, 0); }, "below the count");
}

// The total's sums of the moving pixel are the definition's; the still pixel's are sample 0's;
// the counts are the samples taken.
void expectTotal(const std::vector<glm::vec4>& total, const std::vector<float>& samples, const std::string& what) {
  EXPECT_EQ(bitsOf(total[0]), std::bit_cast<uint32_t>(definedTotal(samples))) << what;
  EXPECT_EQ(total[0].w, float(samples.size())) << what;
  EXPECT_EQ(bitsOf(total[1]), std::bit_cast<uint32_t>(samples[0])) << what;
  EXPECT_EQ(total[1].w, 1.0f) << what;
}

TEST(ReferenceSumTreeTest, ASingleRenderAddsInTheDefinedOrderWithAnyNumberOfSlots) {
  std::mt19937 random(7);
  for (uint32_t n = 1; n <= 300; ++n) {
    const std::vector<float> samples = samplesOf(n, random);
    for (const uint32_t slots : {3u, 4u, 10u})
      expectTotal(renderShard(samples, {0, n}, slots).total, samples, std::to_string(n) + " samples, " +
                                                                            std::to_string(slots) + " slots");
  }
  // Three slots park nodes in host memory as they go; ten keep 1000 samples' nodes on the
  // device, but sample 0's.
  std::vector<float> many = samplesOf(1000, random);
  EXPECT_GT(renderShard(many, {0, 1000}, 3).parked, 100u);
  EXPECT_EQ(renderShard(many, {0, 1000}, 10).parked, 1u);
}

TEST(ReferenceSumTreeTest, ShardsMergeToTheSingleRenderInAnyOrder) {
  std::mt19937 random(11);
  for (const uint32_t n : {1u, 2u, 3u, 5u, 16u, 17u, 64u, 100u, 255u, 256u, 257u, 1000u}) {
    const std::vector<float> samples = samplesOf(n, random);
    for (const uint32_t k : {1u, 2u, 3u, 7u, 13u, 64u, n}) {
      if (k > n) continue;
      for (const uint32_t slots : {3u, 4u, 10u}) {
        const std::string what =
            std::to_string(n) + " samples, " + std::to_string(k) + " shards, " + std::to_string(slots) + " slots";
        std::vector<Part> parts;
        for (uint32_t i = 0; i < k; ++i) parts.push_back(renderShard(samples, passes::shardSamples(n, i, k), slots).part);
        expectTotal(mergeParts(parts, slots), samples, what);
        std::reverse(parts.begin(), parts.end());
        expectTotal(mergeParts(parts, slots), samples, what + " reversed");
        std::shuffle(parts.begin(), parts.end(), random);
        expectTotal(mergeParts(parts, 3), samples, what + " shuffled, merged in three slots");
      }
    }
  }
}

TEST(ReferenceSumTreeTest, AShardResumedFromItsNodesEndsAsOneThatRanThrough) {
  std::mt19937 random(13);
  const std::vector<float> samples = samplesOf(200, random);
  const SampleRange shard = passes::shardSamples(200, 1, 3);
  const Part whole = renderShard(samples, shard, 3).part;
  for (const uint32_t stop : {1u, 5u, 32u, 60u}) {
    const Part half = renderShard(samples, shard, 3, nullptr, stop).part;
    const Part resumed = renderShard(samples, shard, 3, &half).part;
    ASSERT_EQ(resumed.nodes, whole.nodes) << stop;
    for (size_t i = 0; i < whole.sums.size(); ++i)
      EXPECT_EQ(bitsOf(resumed.sums[i][0]), bitsOf(whole.sums[i][0])) << stop << " node " << i;
  }
}

// Pairwise sums: a million samples of 0.1 average to 0.1 within a few float steps, where a
// running sum drifts by far more.
TEST(ReferenceSumTreeTest, PairwiseSumsKeepTheMeanOfManySamples) {
  const uint32_t n = 1u << 20;
  const std::vector<float> samples(n, 0.1f);
  const float tree = definedTotal(samples) / float(n);
  float running = 0.0f;
  for (const float s : samples) running += s;
  EXPECT_NEAR(tree, 0.1f, 4e-8f);
  EXPECT_GT(std::abs(running / float(n) - 0.1f), 1e-4f);
}

// However many samples: a shard holds at most two nodes a level, and sample 0's.
TEST(ReferenceSumTreeTest, AShardHoldsFewNodes) {
  for (const uint32_t n : {2u, 100u, 1024u, 4097u, 65536u}) {
    const uint32_t levels = static_cast<uint32_t>(std::bit_width(n - 1));
    for (const uint32_t k : {1u, 3u, 7u, 61u}) {
      if (k > n) continue;
      for (uint32_t i = 0; i < k; ++i) {
        const SampleRange shard = passes::shardSamples(n, i, k);
        size_t most = 0;
        for (uint32_t done = 0; done <= shard.size(); done += std::max(1u, shard.size() / 97))
          most = std::max(most, passes::heldNodes(shard, done).size());
        EXPECT_LE(most, 2 * levels + 1) << n << " " << i << "/" << k;
        for (const SumNode& node : passes::heldNodes(shard, shard.size()))
          EXPECT_TRUE(isTreeNode(node, n)) << text(node) << " (level " << node.level << ", start " << node.start << ") of " << n;
      }
    }
  }
}

TEST(ReferenceSumTreeTest, NodesOfTheTree) {
  EXPECT_TRUE(isTreeNode({2, 4}, 16));
  EXPECT_FALSE(isTreeNode({1, 1}, 16));  // misaligned
  EXPECT_FALSE(isTreeNode({4, 0}, 16));  // past 15 leaves
  EXPECT_TRUE(isTreeNode(SumNode::firstSample(), 1));
  EXPECT_TRUE(SumNode({1, 4}).isLeftOf({1, 6}));
  EXPECT_FALSE(SumNode({1, 6}).isLeftOf({1, 8}));  // a right half
  EXPECT_FALSE(SumNode({1, 4}).isLeftOf({0, 6}));
  EXPECT_FALSE(SumNode::firstSample().isLeftOf({0, 0}));
  EXPECT_EQ(text(SumNode({2, 4})), "samples 5..8");
  EXPECT_EQ(SumNode::firstSample().firstSampleIndex(), 0u);
  EXPECT_EQ(SumNode({2, 4}).firstSampleIndex(), 5u);
  EXPECT_EQ(SumNode::ofSample(9), SumNode({0, 8}));
}

}  // namespace
}  // namespace hmb::test
