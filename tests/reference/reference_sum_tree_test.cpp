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
#include <vector>

#include <gtest/gtest.h>

#include "runtime/passes/reference_sum_tree.h"
#include "tests/support/expect_error.h"

namespace hmb::test {
namespace {

using passes::FoldProgram;
using passes::FoldStep;
using passes::SampleRange;
using passes::ShardSumTree;
using passes::SumNode;
using passes::SumStep;

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

// A shard's render of one pixel, as accumulate_sample does it: the nodes it holds at the end.
struct Part {
  std::map<SumNode, float> nodes;
};

Part renderShard(const std::vector<float>& samples, SampleRange shard) {
  ShardSumTree tree(static_cast<uint32_t>(samples.size()), shard);
  std::vector<float> slots(tree.slotCount(), std::numeric_limits<float>::quiet_NaN());
  for (uint32_t s = shard.begin; s < shard.end; ++s) {
    const SumStep step = tree.add();
    float node = samples[s];
    for (uint32_t level = 0; level < step.foldLevels; ++level) node = slots.at(step.foldSlot + level) + node;
    slots.at(step.targetSlot) = node;
  }
  Part part;
  for (const ShardSumTree::Held& held : tree.held()) part.nodes[held.node] = slots[held.slot];
  return part;
}

// fold_sums playing a program; loads come from the parts.
float runFold(const FoldProgram& program, std::vector<float> slots, const std::map<SumNode, float>& loadable) {
  slots.resize(std::max<size_t>(slots.size(), program.slotCount), std::numeric_limits<float>::quiet_NaN());
  for (const FoldStep& step : program.steps) {
    if (step.kind == FoldStep::Kind::Load)
      slots.at(step.left) = loadable.at(step.node);
    else
      slots.at(step.left) = slots.at(step.left) + slots.at(step.right);
  }
  return slots.at(*program.result);
}

float mergeParts(uint32_t samples, const std::vector<Part>& parts) {
  std::vector<SumNode> nodes;
  std::map<SumNode, float> loadable;
  for (const Part& part : parts)
    for (const auto& [node, sum] : part.nodes) {
      nodes.push_back(node);
      loadable[node] = sum;
    }
  return runFold(passes::foldProgram(samples, {}, nodes, 0), {}, loadable);
}

// A whole render: its held nodes stay in their slots and are added there.
float singleRender(const std::vector<float>& samples) {
  const uint32_t n = static_cast<uint32_t>(samples.size());
  ShardSumTree tree(n, {0, n});
  std::vector<float> slots(tree.slotCount(), std::numeric_limits<float>::quiet_NaN());
  for (uint32_t s = 0; s < n; ++s) {
    const SumStep step = tree.add();
    float node = samples[s];
    for (uint32_t level = 0; level < step.foldLevels; ++level) node = slots.at(step.foldSlot + level) + node;
    slots.at(step.targetSlot) = node;
  }
  return runFold(passes::foldProgram(n, tree.held(), {}, tree.slotCount()), slots, {});
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

TEST(ReferenceSumTreeTest, ASingleRenderAddsInTheDefinedOrder) {
  std::mt19937 random(7);
  for (uint32_t n = 1; n <= 300; ++n) {
    const std::vector<float> samples = samplesOf(n, random);
    EXPECT_EQ(std::bit_cast<uint32_t>(singleRender(samples)), std::bit_cast<uint32_t>(definedTotal(samples))) << n;
  }
}

TEST(ReferenceSumTreeTest, ShardsMergeToTheSingleRenderInAnyOrder) {
  std::mt19937 random(11);
  for (const uint32_t n : {1u, 2u, 3u, 5u, 16u, 17u, 64u, 100u, 255u, 256u, 257u, 1000u}) {
    const std::vector<float> samples = samplesOf(n, random);
    const uint32_t single = std::bit_cast<uint32_t>(singleRender(samples));
    for (const uint32_t k : {1u, 2u, 3u, 7u, 13u, 64u, n}) {
      if (k > n) continue;
      std::vector<Part> parts;
      for (uint32_t i = 0; i < k; ++i) parts.push_back(renderShard(samples, passes::shardSamples(n, i, k)));
      EXPECT_EQ(std::bit_cast<uint32_t>(mergeParts(n, parts)), single) << n << " samples, " << k << " shards";
      std::reverse(parts.begin(), parts.end());
      EXPECT_EQ(std::bit_cast<uint32_t>(mergeParts(n, parts)), single) << n << " samples, " << k << " shards reversed";
      std::shuffle(parts.begin(), parts.end(), random);
      EXPECT_EQ(std::bit_cast<uint32_t>(mergeParts(n, parts)), single) << n << " samples, " << k << " shards shuffled";
    }
  }
}

// Pairwise sums: a million samples of 0.1 average to 0.1 within a few float steps, where a
// running sum drifts by far more.
TEST(ReferenceSumTreeTest, PairwiseSumsKeepTheMeanOfManySamples) {
  const uint32_t n = 1u << 20;
  const std::vector<float> samples(n, 0.1f);
  const float tree = singleRender(samples) / float(n);
  float running = 0.0f;
  for (const float s : samples) running += s;
  EXPECT_NEAR(tree, 0.1f, 4e-8f);
  EXPECT_GT(std::abs(running / float(n) - 0.1f), 1e-4f);
}

// However many samples or shards: a shard holds at most two nodes a level, and a merge, which
// loads them one at a time, uses about one slot a level.
TEST(ReferenceSumTreeTest, ShardsAndMergesHoldFewNodes) {
  for (const uint32_t n : {2u, 100u, 1024u, 4097u, 65536u}) {
    const uint32_t levels = static_cast<uint32_t>(std::bit_width(n - 1));
    for (const uint32_t k : {1u, 3u, 7u, 61u}) {
      if (k > n) continue;
      std::vector<SumNode> all;
      for (uint32_t i = 0; i < k; ++i) {
        ShardSumTree tree(n, passes::shardSamples(n, i, k));
        size_t most = 0;
        while (!tree.finished()) {
          tree.add();
          most = std::max(most, tree.held().size());
        }
        EXPECT_LE(most, 2 * levels + 1) << n << " " << i << "/" << k;
        EXPECT_LE(tree.slotCount(), 2 * levels + 1);
        for (const ShardSumTree::Held& held : tree.held()) all.push_back(held.node);
      }
      const FoldProgram program = passes::foldProgram(n, {}, all, 0);
      EXPECT_LE(program.slotCount, levels + 2) << n << " samples, " << k << " shards";
    }
  }
}

TEST(ReferenceSumTreeTest, AFoldRefusesNodesThatAreNotTheTreesOrOverlap) {
  expectError([] { passes::foldProgram(16, {}, {{1, 1}}, 0); }, "not a node of the sum tree");  // misaligned
  expectError([] { passes::foldProgram(16, {}, {{4, 0}}, 0); }, "not a node of the sum tree");  // past 15 leaves
  expectError([] { passes::foldProgram(16, {}, {{2, 4}, {1, 6}}, 0); }, "overlap");
  expectError([] { passes::foldProgram(16, {}, {{1, 4}, {1, 4}}, 0); }, "both hold");
  expectError([] { passes::foldProgram(16, {}, {SumNode::firstSample(), SumNode::firstSample()}, 0); }, "both hold");
  EXPECT_EQ(SumNode({2, 4}).text(), "samples 5..8");
}

}  // namespace
}  // namespace hmb::test
