// list_shutter_rays.comp against the C++ reference on random and adversarial layers (which
// pixels are listed, with how many rays, and the list's indirect dispatch), and the rule's
// pieces by hand: object and colour edges, rays per blur length, strata offsets and the list
// entry's packing.
#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "tests/hybrid/hybrid_harness.h"
#include "tests/hybrid/hybrid_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace hybrid;
using passes::RayMaskParameters;

RayMaskParameters parametersWith(float maxSpeed, float velocityScale, uint32_t tileSize = 13) {
  RayMaskParameters p;
  p.blur.tileSize = tileSize;  // odd: partial 8x8 blocks and partial border tiles
  p.blur.velocityScale = velocityScale;
  p.blur.maxSpeed = maxSpeed;
  p.blur.softZExtent = 0.03f;
  p.edgeThreshold = 0.9f;
  return p;
}

// Colours for a layer: each object a colour of its own, half of them striped across x (8 px
// stripes) by steps some above and some below HMB_SHUTTER_RAY_COLOR_STEP, and a few pixels far
// out of the display's range.
MaskLayer withColors(MaskLayer layer, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::map<uint32_t, std::pair<glm::vec3, float>> looks;  // per object: base colour, stripe step
  layer.color.resize(layer.objectId.size());
  for (size_t i = 0; i < layer.objectId.size(); ++i) {
    auto [it, added] = looks.try_emplace(layer.objectId[i]);
    if (added) it->second = {glm::vec3(unit(rng), unit(rng), unit(rng)), unit(rng) < 0.5f ? 0.0f : 0.3f * unit(rng)};
    const auto [base, step] = it->second;
    const uint32_t x = uint32_t(i % layer.width);
    layer.color[i] = base + glm::vec3(((x / 8) % 2 == 0) ? 0.0f : step);
    if (unit(rng) < 0.01f) layer.color[i] *= 50.0f;
  }
  return layer;
}

// Every pixel's rays as the device listed them equal the reference's; the list's dispatch
// covers it in groups of HMB_MASK_LIST_GROUP. groupsWanted: the list's own groups (unset: the
// device's type decides). Returns the pixels listed.
size_t expectListMatches(const MaskLayer& layer, const RayMaskParameters& p, uint32_t strata, const std::string& what,
                         std::optional<uint32_t> groupsWanted = std::nullopt) {
  const ShutterRayListReadback device = runShutterRayList(VulkanTest::context(), layer, p, strata, groupsWanted);
  const std::vector<uint32_t> reference = shutterRays(layer, p, strata);
  size_t listed = 0, wrong = 0;
  for (size_t i = 0; i < reference.size(); ++i) {
    listed += reference[i] != 0u;
    if (device.rays[i] == reference[i]) continue;
    if (++wrong <= 5)
      ADD_FAILURE() << what << ": pixel (" << i % layer.width << ", " << i / layer.width << ") device "
                    << device.rays[i] << " rays, reference " << reference[i] << " (velocity " << layer.velocity[i].x
                    << "," << layer.velocity[i].y << ", object " << layer.objectId[i] << ")";
  }
  EXPECT_EQ(wrong, 0u) << what;
  EXPECT_EQ(device.counters.count, listed) << what;
  const uint32_t groups = (device.counters.count + HMB_MASK_LIST_GROUP - 1) / HMB_MASK_LIST_GROUP;
  EXPECT_EQ(device.counters.dispatchX, std::min(groups, HMB_SHUTTER_RAY_GROUPS_PER_ROW)) << what;
  EXPECT_EQ(device.counters.dispatchY, (groups + HMB_SHUTTER_RAY_GROUPS_PER_ROW - 1) / HMB_SHUTTER_RAY_GROUPS_PER_ROW)
      << what;
  EXPECT_EQ(device.counters.dispatchZ, groups == 0 ? 0u : 1u) << what;
  EXPECT_EQ(device.counters.rayCount, 0u) << what << ": nothing traced yet";
  return listed;
}

using HybridShutterRaysTest = VulkanTest;

TEST_F(HybridShutterRaysTest, ListMatchesReferenceOnRandomLayers) {
  std::mt19937 rng(23);
  struct Case {
    uint32_t width, height;
    RayMaskParameters p;
    uint32_t strata;
  };
  const Case cases[] = {{37, 23, parametersWith(40.0f, 1.0f), 8},     {64, 64, parametersWith(40.0f, 3.0f), 16},
                        {129, 71, parametersWith(40.0f, 1.0f), 2},    {1, 41, parametersWith(40.0f, 1.0f), 8},
                        {53, 1, parametersWith(40.0f, 1.0f), 4},      {1, 1, parametersWith(40.0f, 1.0f), 8},
                        {61, 47, parametersWith(5.0f, 1.0f), 8},      // clamped to 5 px
                        {61, 47, parametersWith(40.0f, 0.1f), 8},     // mostly sub-pixel
                        {200, 90, parametersWith(40.0f, 1.0f, 40), 8}};  // over HMB_MASK_LIST_GROUP entries
  size_t listed = 0, pixels = 0;
  for (const Case& c : cases) {
    const MaskLayer layer = withColors(randomMaskLayer(c.width, c.height, rng), rng);
    const std::string what =
        std::to_string(c.width) + "x" + std::to_string(c.height) + " strata " + std::to_string(c.strata);
    listed += expectListMatches(layer, c.p, c.strata, what);
    pixels += layer.objectId.size();
    // A group per block (a GPU's shape) and a few groups taking runs of blocks list the same.
    for (const uint32_t groups : {0u, 3u})
      expectListMatches(layer, c.p, c.strata, what + ", " + std::to_string(groups) + " groups wanted", groups);
  }
  // Some pixels, not all: the rule decides.
  EXPECT_GT(listed, 100u);
  EXPECT_LT(listed, pixels / 2);
}

TEST_F(HybridShutterRaysTest, ListMatchesReferenceOnAdversarialLayers) {
  std::mt19937 rng(29);
  size_t listed = 0;
  for (int round = 0; round < 5; ++round) {
    const MaskLayer layer = withColors(adversarialMaskLayer(43, 37, rng), rng);
    for (const float velocityScale : {1.0f, 2.0f})
      listed += expectListMatches(layer, parametersWith(40.0f, velocityScale), 8,
                                  "round " + std::to_string(round) + " scale " + std::to_string(velocityScale));
  }
  EXPECT_GT(listed, 100u);
}

// Under a ray budget: every listed pixel's priority bucket is the reference's, and the pixels
// kept are the reference's, whatever order the device listed them in (the threshold bucket's
// ties go to the lower pixel indices); they hold at most the budget's rays, and every kept pixel
// ranks at least as high as every pixel left out. Budgets from one ray (nothing fits) to more
// than the list holds, on random and adversarial layers.
void expectBudgetMatches(const MaskLayer& layer, const RayMaskParameters& p, uint32_t strata, const std::string& what,
                         size_t& keptPixels, size_t& cutCases) {
  std::vector<uint32_t> priorities;
  const std::vector<uint32_t> rays = shutterRays(layer, p, strata, &priorities);
  uint64_t listedRays = 0;
  for (const uint32_t n : rays) listedRays += n;
  for (const double share : {0.0, 0.1, 0.5, 0.9, 2.0}) {
    const uint32_t budget = std::max<uint32_t>(1, uint32_t(share * double(listedRays)));
    const std::string with = what + ", budget " + std::to_string(budget) + " of " + std::to_string(listedRays);
    const ShutterRayListReadback device = runShutterRayList(VulkanTest::context(), layer, p, strata, std::nullopt, budget);
    ASSERT_EQ(device.rays, rays) << with;
    size_t wrongPriorities = 0;
    for (size_t i = 0; i < rays.size(); ++i)
      if (rays[i] != 0 && device.priorities[i] != priorities[i] && ++wrongPriorities <= 5)
        ADD_FAILURE() << with << ": pixel " << i << " priority " << device.priorities[i] << ", reference "
                      << priorities[i];
    EXPECT_EQ(wrongPriorities, 0u) << with;
    const std::vector<bool> kept = keptByBudget(rays, priorities, budget);
    EXPECT_EQ(device.kept, kept) << with;
    uint64_t keptRays = 0;
    size_t keptCount = 0;
    for (size_t i = 0; i < rays.size(); ++i)
      if (device.kept[i]) {
        keptRays += rays[i];
        ++keptCount;
      }
    EXPECT_EQ(device.keptCounters.count, keptCount) << with;
    EXPECT_EQ(device.keptCounters.rayCount, 0u) << with << ": nothing traced yet";
    const uint32_t groups = (device.keptCounters.count + HMB_MASK_LIST_GROUP - 1) / HMB_MASK_LIST_GROUP;
    EXPECT_EQ(device.keptCounters.dispatchX, std::min(groups, HMB_SHUTTER_RAY_GROUPS_PER_ROW)) << with;
    EXPECT_EQ(device.keptCounters.dispatchZ, groups == 0 ? 0u : 1u) << with;
    EXPECT_LE(keptRays, budget) << with;
    if (listedRays > budget) {
      // Every kept pixel ranks at least as high as every pixel left out.
      uint32_t lowestKept = HMB_RAY_BUDGET_BUCKETS, highestLeft = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        if (rays[i] == 0) continue;
        if (device.kept[i])
          lowestKept = std::min(lowestKept, priorities[i]);
        else
          highestLeft = std::max(highestLeft, priorities[i]);
      }
      if (keptCount != 0) {
        EXPECT_GE(lowestKept, highestLeft) << with;
      }
      ++cutCases;
    } else {
      EXPECT_EQ(keptRays, listedRays) << with << ": the whole list fits";
    }
    keptPixels += keptCount;
  }
}

// A still frame lists nothing and dispatches no ray.
TEST_F(HybridShutterRaysTest, StillLayerListsNothing) {
  std::mt19937 rng(31);
  MaskLayer layer = randomMaskLayer(40, 30, rng);
  std::fill(layer.velocity.begin(), layer.velocity.end(), glm::vec2(0.0f));
  EXPECT_EQ(expectListMatches(layer, parametersWith(40.0f, 1.0f), 8, "still"), 0u);
}

// The by-hand cases' layer: 30 x 6 pixels of object 1 at depth 2, all moving 3 px right (one
// tile of 30 px holds it).
MaskLayer movingStrip() {
  MaskLayer layer;
  layer.width = 30;
  layer.height = 6;
  const size_t pixels = size_t(layer.width) * layer.height;
  layer.normalDepth.assign(pixels, glm::vec4(0.0f, 0.0f, 1.0f, 2.0f));
  layer.velocity.assign(pixels, glm::vec2(3.0f, 0.0f));
  layer.objectId.assign(pixels, 1u);
  return layer;
}

// By hand: object 2 fills columns 10-19 of a 30 x 6 image over object 1; everything moves
// 3 px right, so a pixel is listed when its path (3 px either way, and a pixel more: 4) meets
// the other object: columns 6-13 and 16-23. Columns 14 and 15 see object 2 from 10 to 19.
// Then only object 2 moves: the still pixels of object 1 take the tile's fastest path, 4 px.
TEST_F(HybridShutterRaysTest, PathsThatCrossAnEdgeByHand) {
  MaskLayer layer = movingStrip();
  const size_t pixels = layer.objectId.size();
  for (uint32_t y = 0; y < layer.height; ++y)
    for (uint32_t x = 10; x < 20; ++x) layer.objectId[y * layer.width + x] = 2u;
  const std::vector<uint32_t> reference = shutterRays(layer, parametersWith(40.0f, 1.0f, 30), 8);
  for (uint32_t x = 0; x < layer.width; ++x) {
    const bool listed = (x >= 6 && x <= 13) || (x >= 16 && x <= 23);
    EXPECT_EQ(reference[x], listed ? 2u : 0u) << "column " << x;  // 3 px of blur: 2 rays
  }
  expectListMatches(layer, parametersWith(40.0f, 1.0f, 30), 8, "by hand");
  for (uint32_t i = 0; i < pixels; ++i)
    if (layer.objectId[i] == 1u) layer.velocity[i] = glm::vec2(0.0f);
  const std::vector<uint32_t> stillBackground = shutterRays(layer, parametersWith(40.0f, 1.0f, 30), 8);
  EXPECT_EQ(stillBackground, reference) << "a still pixel walks its tile's fastest path";
  expectListMatches(layer, parametersWith(40.0f, 1.0f, 30), 8, "by hand, still background");
}

// By hand: one object, its colour stepping at column 15 of a 30 x 6 image, everything moving
// 3 px right: the step lists the pixels whose path (4 px either way) reaches it, columns 11-18,
// when the step passes HMB_SHUTTER_RAY_COLOR_STEP in the colour's key, and none when it does not.
TEST_F(HybridShutterRaysTest, ColourStepsOnOneObjectByHand) {
  MaskLayer layer = movingStrip();
  const size_t pixels = layer.objectId.size();
  // Keys sqrt(0.25) = 0.5 on the left; 0.64 (key 0.8) steps past 0.1, 0.3025 (key 0.55) does not.
  for (const float right : {0.64f, 0.3025f}) {
    layer.color.assign(pixels, glm::vec3(0.25f));
    for (size_t i = 0; i < pixels; ++i)
      if (i % layer.width >= 15) layer.color[i] = glm::vec3(0.25f, right, 0.25f);
    const bool steps = right > 0.5f;
    const std::vector<uint32_t> reference = shutterRays(layer, parametersWith(40.0f, 1.0f, 30), 8);
    for (uint32_t x = 0; x < layer.width; ++x)
      EXPECT_EQ(reference[x], steps && x >= 11 && x <= 18 ? 2u : 0u) << "column " << x << ", right " << right;
    expectListMatches(layer, parametersWith(40.0f, 1.0f, 30), 8, steps ? "a colour step" : "a colour change under the step");
  }
}

// Object 2 fills a 400 x 128 image but its last 20 columns and moves 300 px right; object 3
// there is still. A pixel is listed when its walk (301 px either way) meets the other object,
// and those more than 301 px from it walk the whole way. With tiles of 128 px, a group per tile
// left 256 pixels to a lane, near 75,000 loop rounds, past the 65535 llvmpipe 22.3 allows an
// invocation (it ends the loops silently: a lane's last pixels were never listed). One group
// wanted: its run is cut to what the budget holds, and the list is the reference's. A driver
// without a budget takes the one group.
TEST_F(HybridShutterRaysTest, LongWalksCutTheRunsToTheLoopBudget) {
  const uint32_t width = 400, height = 128, tileSize = 128;
  const MaskLayer layer = movingOntoStillColumns(width, height, 20, {300.0f, 0.0f});
  const RayMaskParameters p = parametersWith(400.0f, 1.0f, tileSize);
  EXPECT_GT(expectListMatches(layer, p, 8, "long walks, one group wanted", 1u), size_t(300) * height);
  const ShutterRayListReadback device = runShutterRayList(context(), layer, p, 8, 1u);
  ASSERT_EQ(device.maskCounters.tileCount, 3u) << "the last tile, 16 still columns, does not move";
  const uint32_t blocks = 3 * (tileSize / 8) * (tileSize / 8);
  EXPECT_GT(uint64_t(blocks) * 301, 65535u) << "one run would pass the budget";
  // A block's walks take at most s + 3 rounds for the larger s of the speed bound and the tile,
  // and its tile 2 more.
  const std::optional<uint32_t> budget = context().profile().loopBudget;
  const uint32_t maxRun = budget ? *budget / (400 + 6) : blocks;
  EXPECT_EQ(device.maskCounters.dispatches[HMB_RAY_MASK_DISPATCH_SHUTTER_BLOCKS].x, (blocks + maxRun - 1) / maxRun);
  EXPECT_EQ(device.maskCounters.dispatches[HMB_RAY_MASK_DISPATCH_SHUTTER_BLOCKS].y, 1u);
}

TEST(HybridShutterRaysRuleTest, RaysFollowTheBlurLength) {
  // One ray per HMB_SHUTTER_RAY_SPACING pixels, a power of two from 2 to the strata.
  EXPECT_EQ(gpu::shutterRaysFor(0.5f, 8), 2u);
  EXPECT_EQ(gpu::shutterRaysFor(4.0f, 8), 2u);
  EXPECT_EQ(gpu::shutterRaysFor(4.01f, 8), 4u);
  EXPECT_EQ(gpu::shutterRaysFor(8.01f, 8), 8u);
  EXPECT_EQ(gpu::shutterRaysFor(100.0f, 8), 8u);
  EXPECT_EQ(gpu::shutterRaysFor(100.0f, 16), 16u);
  EXPECT_EQ(gpu::shutterRaysFor(100.0f, 2), 2u);
  EXPECT_EQ(gpu::shutterRaysFor(std::numeric_limits<float>::infinity(), 4), 4u);
}

TEST(HybridShutterRaysRuleTest, EntriesPackPixelAndRays) {
  for (const uint32_t rays : {2u, 4u, 8u, 16u})
    for (const uint32_t pixel : {0u, 1u, 12345u, (1u << HMB_SHUTTER_ENTRY_PIXEL_BITS) - 1u}) {
      const uint32_t entry = gpu::shutterRayEntry(pixel, rays);
      EXPECT_EQ(gpu::shutterRayEntryPixel(entry), pixel);
      EXPECT_EQ(gpu::shutterRayEntryRays(entry), rays);
    }
  // The largest image (16384 x 16384) fits the pixel bits.
  EXPECT_LE(uint64_t(16384) * 16384, uint64_t(1) << HMB_SHUTTER_ENTRY_PIXEL_BITS);
}

// Each pixel's rays take every (strata / rays)-th stratum from its first: all strata are used
// when rays == strata, and over many pixels each offset comes up about equally often.
TEST(HybridShutterRaysRuleTest, FirstStrataSpreadOverPixels) {
  for (uint32_t pixel = 0; pixel < 100; ++pixel) EXPECT_EQ(gpu::shutterRayFirstStratum(pixel, 8, 8), 0u);
  std::vector<int> seen(4, 0);
  for (uint32_t pixel = 0; pixel < 4000; ++pixel) {
    const uint32_t first = gpu::shutterRayFirstStratum(pixel, 2, 8);
    ASSERT_LT(first, 4u);
    ++seen[first];
  }
  for (const int n : seen) EXPECT_NEAR(n, 1000, 150);
}

TEST_F(HybridShutterRaysTest, RayBudgetKeepsThePixelsTheReferenceKeeps) {
  std::mt19937 rng(37);
  size_t kept = 0, cut = 0;
  for (const auto& [width, height, strata] : {std::tuple{61u, 47u, 8u}, std::tuple{129u, 71u, 16u}, std::tuple{1u, 41u, 4u}})
    expectBudgetMatches(withColors(randomMaskLayer(width, height, rng), rng), parametersWith(40.0f, 1.0f), strata,
                        "random " + std::to_string(width) + "x" + std::to_string(height), kept, cut);
  for (int round = 0; round < 3; ++round)
    expectBudgetMatches(withColors(adversarialMaskLayer(43, 37, rng), rng), parametersWith(40.0f, 2.0f), 8,
                        "adversarial round " + std::to_string(round), kept, cut);
  // One colour and one object edge: every listed pixel in few buckets, ties decided by order.
  MaskLayer strip = movingStrip();
  for (uint32_t y = 0; y < strip.height; ++y)
    for (uint32_t x = 10; x < 20; ++x) strip.objectId[y * strip.width + x] = 2u;
  strip.color.assign(strip.objectId.size(), glm::vec3(0.5f));
  expectBudgetMatches(strip, parametersWith(40.0f, 1.0f, 30), 8, "ties", kept, cut);
  EXPECT_GT(kept, 100u);
  EXPECT_GT(cut, 5u);
}

// The priority's pieces by hand: the contrast times the share of the path over something else,
// per ray; buckets an eighth of an octave, 0 for nothing, capped at both ends.
TEST(HybridShutterRaysRuleTest, PriorityRanksTheErrorPerRay) {
  EXPECT_FLOAT_EQ(gpu::shutterRayPriority(0.5f, 3, 12, 2), 0.5f * 0.25f / 2.0f);
  EXPECT_EQ(gpu::shutterRayPriority(0.5f, 0, 12, 2), 0.0f);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(0.0f), 0u);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(-1.0f), 0u);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(std::numeric_limits<float>::quiet_NaN()), 0u);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(1.0f), HMB_RAY_BUDGET_BUCKETS - 1);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(std::numeric_limits<float>::infinity()), HMB_RAY_BUDGET_BUCKETS - 1);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(0.5f), HMB_RAY_BUDGET_BUCKETS - 1 - 8);  // an octave: 8 buckets
  EXPECT_EQ(gpu::shutterRayPriorityBucket(1e-30f), 1u);
  EXPECT_EQ(gpu::shutterRayPriorityBucket(std::numeric_limits<float>::denorm_min()), 1u);
  // Monotonic: a larger priority never takes a lower bucket.
  uint32_t last = 0;
  for (float p = 1e-12f; p < 2.0f; p *= 1.01f) {
    const uint32_t b = gpu::shutterRayPriorityBucket(p);
    EXPECT_GE(b, last) << p;
    last = b;
  }
}

}  // namespace
}  // namespace hmb::test
