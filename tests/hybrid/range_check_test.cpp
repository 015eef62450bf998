// range_check.comp and size_list_dispatch.comp: the ray mask against the reference (walked
// over the device's own edge mask, so edge pixels near the threshold cannot blur the
// comparison), the compacted list holding each masked pixel once, the count, and the indirect
// dispatch it sizes, down to an empty mask dispatching nothing and a list too long for one row
// of groups.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kernels/ray_mask/ray_mask_layout.h"
#include "tests/hybrid/hybrid_harness.h"
#include "tests/hybrid/hybrid_reference.h"
#include "tests/mblur/mblur_harness.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace hybrid;
using passes::RayMaskParameters;

RayMaskParameters parametersWith(float edgeThreshold, float maxSpeed = 40.0f, float velocityScale = 1.0f) {
  RayMaskParameters p;
  p.blur.tileSize = 13;  // the moving-tile list's tiles: odd, partial 8x8 blocks and partial border tiles
  p.blur.velocityScale = velocityScale;
  p.blur.maxSpeed = maxSpeed;
  p.blur.softZExtent = 0.03f;
  p.edgeThreshold = edgeThreshold;
  return p;
}

// A random layer of the given size for the coverage composite's mask (mask_coverage tests
// every mask pixel), at threshold 0.5.
struct CoverageCase {
  MaskLayer layer;
  RayMaskParameters p;
};
CoverageCase coverageCase(uint32_t seed, uint32_t width, uint32_t height) {
  std::mt19937 rng(seed);
  CoverageCase c{randomMaskLayer(width, height, rng), parametersWith(0.5f)};
  c.p.listOnlyUncovered = true;
  return c;
}

// The dispatch of `count` listed pixels, 64 per group in rows of at most 65535 groups, written
// out here rather than taken from the reference.
void expectDispatchFor(const gpu::RayMaskCounters& c, uint64_t count, const std::string& what) {
  const uint64_t groups = (count + 63) / 64;
  EXPECT_EQ(c.maskCount, count) << what;
  const gpu::IndirectDispatch& front = c.dispatches[HMB_RAY_MASK_DISPATCH_MASK];
  EXPECT_EQ(front.x, std::min<uint64_t>(groups, 65535)) << what;
  EXPECT_EQ(front.y, groups == 0 ? 0 : (groups + 65534) / 65535) << what;
  EXPECT_EQ(front.z, 1u) << what;
  EXPECT_EQ(c.rayCount, 0u) << what << ": no reveal ran";
  const gpu::RayMaskCounters mirror = dispatchFor(uint32_t(count), c.unrevealedCount);
  EXPECT_EQ(front.x, mirror.dispatches[HMB_RAY_MASK_DISPATCH_MASK].x) << what;
  EXPECT_EQ(front.y, mirror.dispatches[HMB_RAY_MASK_DISPATCH_MASK].y) << what;
  // The coverage composite runs over the unrevealed pixels at the list's back.
  EXPECT_EQ(c.maskPixels, count + c.unrevealedCount) << what;
  const uint64_t backGroups = (uint64_t(c.unrevealedCount) + 63) / 64;
  const gpu::IndirectDispatch& back = c.dispatches[HMB_RAY_MASK_DISPATCH_UNREVEALED];
  EXPECT_EQ(back.x, std::min<uint64_t>(backGroups, 65535)) << what;
  EXPECT_EQ(back.y, backGroups == 0 ? 0 : (backGroups + 65534) / 65535) << what;
  EXPECT_EQ(back.x, mirror.dispatches[HMB_RAY_MASK_DISPATCH_UNREVEALED].x) << what;
  EXPECT_EQ(back.z, 1u) << what;
}

// The longest run of blocks one range check group may take: its walks, at most 4 s + 16 loop
// rounds a pixel for a walk speed s (the largest speed, twice it along curved paths), stay
// within the driver's loop budget where it has one (ray_mask_layout.h), written out here.
uint64_t rangeRunLimit(const RayMaskParameters& p, std::optional<uint32_t> loopBudget) {
  if (!loopBudget) return HMB_RANGE_CHECK_MAX_RUN;
  const bool curved = (p.blur.flags & HMB_GATHER_FLAG_CURVED_PATH) != 0u;
  const float walkSpeed = (curved ? 2.0f : 1.0f) * p.blur.maxSpeed;
  const uint64_t perBlock = 4u * static_cast<uint64_t>(std::ceil(walkSpeed)) + 17u;
  return std::clamp<uint64_t>(*loopBudget / perBlock, 1u, HMB_RANGE_CHECK_MAX_RUN);
}

// The range check's dispatch over `blocks` listed blocks, written out here: a group per block,
// or the groups wanted, more where a group's run would pass rangeRunLimit blocks.
void expectRangeDispatchFor(const RayMaskReadback& device, uint64_t blocks, const RayMaskParameters& p,
                            const std::string& what) {
  ASSERT_TRUE(p.rangeCheckGroups.has_value()) << what;
  const gpu::RayMaskCounters& c = device.counters;
  const uint64_t wanted = *p.rangeCheckGroups, run = rangeRunLimit(p, VulkanTest::context().profile().loopBudget);
  const uint64_t groups = wanted == 0 ? blocks : std::max(std::min(blocks, wanted), (blocks + run - 1) / run);
  EXPECT_EQ(c.dispatches[HMB_RAY_MASK_DISPATCH_RANGE_CHECK].x, std::min<uint64_t>(groups, 65535)) << what;
  EXPECT_EQ(c.dispatches[HMB_RAY_MASK_DISPATCH_RANGE_CHECK].y, groups == 0 ? 0 : (groups + 65534) / 65535) << what;
  EXPECT_EQ(c.dispatches[HMB_RAY_MASK_DISPATCH_RANGE_CHECK].z, 1u) << what;
}

// Mask equal to the reference's range check over the device's edges, every edge pixel in the
// mask (its range starts at itself), the list the masked pixels each once, counters to match,
// the walked blocks the reference's (list_range_blocks); with the range check's groups in any
// shape (one for every block, a block each, a few each taking a run of blocks). Returns the
// mask's size.
size_t expectRayMaskMatchesIn(const MaskLayer& layer, const RayMaskParameters& p, const std::string& what) {
  const RayMaskReadback device = runRayMask(VulkanTest::context(), layer, p);
  std::vector<uint32_t> blocks = device.rangeBlocks;
  std::sort(blocks.begin(), blocks.end());
  EXPECT_EQ(blocks, rangeBlocks(layer, device.edges, p)) << what << ": the range check's blocks";
  EXPECT_EQ(device.counters.rangeBlockCount, blocks.size()) << what;
  expectRangeDispatchFor(device, blocks.size(), p, what);
  const std::vector<uint32_t> reference = rangeCheck(layer.velocity, device.edges, layer.width, layer.height, p);
  EXPECT_EQ(device.mask, reference) << what;
  std::vector<uint32_t> masked;
  for (uint32_t i = 0; i < reference.size(); ++i) {
    if (reference[i] != 0u) masked.push_back(i);
    if (device.edges[i] != 0u) {
      EXPECT_EQ(device.mask[i], 1u) << what << ": edge pixel " << i << " not in the mask";
    }
  }
  std::vector<uint32_t> list = device.list;
  std::sort(list.begin(), list.end());
  EXPECT_EQ(list, masked) << what << ": the list must hold each masked pixel exactly once";
  expectDispatchFor(device.counters, masked.size(), what);
  return masked.size();
}

size_t expectRayMaskMatches(const MaskLayer& layer, RayMaskParameters p, const std::string& what) {
  p.rangeCheckGroups = 1u;
  const size_t oneGroup = expectRayMaskMatchesIn(layer, p, what + ", one group");
  p.rangeCheckGroups = 0u;
  EXPECT_EQ(expectRayMaskMatchesIn(layer, p, what + ", a group per block"), oneGroup) << what;
  p.rangeCheckGroups = 5u;  // runs of blocks over a few groups (or one per block)
  EXPECT_EQ(expectRayMaskMatchesIn(layer, p, what + ", five groups wanted"), oneGroup) << what;
  return oneGroup;
}

// Object 2 (depth 1) over columns 0-19, moving by `velocity`, beside a still, deeper object 3
// (depth 5) over the rest.
MaskLayer slidingStep(uint32_t width, uint32_t height, glm::vec2 velocity) {
  MaskLayer layer{width, height, {}, {}, {}};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool front = x < 20;
      layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, front ? 1.0f : 5.0f);
      layer.velocity.emplace_back(front ? velocity : glm::vec2(0.0f));
      layer.objectId.push_back(front ? 2u : 3u);
    }
  return layer;
}

using HybridRangeCheckTest = VulkanTest;

TEST_F(HybridRangeCheckTest, MaskListAndCountersMatchReferenceOnRandomLayers) {
  std::mt19937 rng(5);
  struct Case {
    uint32_t width, height;
    RayMaskParameters p;
  };
  const Case cases[] = {{37, 23, parametersWith(0.9f)},
                        {64, 64, parametersWith(0.5f)},
                        {129, 71, parametersWith(0.9f)},
                        {1, 41, parametersWith(0.5f)},
                        {53, 1, parametersWith(0.5f)},
                        {1, 1, parametersWith(0.0f)},
                        {61, 47, parametersWith(0.8f, 5.0f)},  // clamped to 5 px
                        {61, 47, parametersWith(0.8f, 40.0f, 2.5f)},
                        {61, 47, parametersWith(0.8f, 40.0f, 0.1f)}};  // mostly sub-pixel
  size_t total = 0, pixels = 0;
  for (const Case& c : cases) {
    const MaskLayer layer = randomMaskLayer(c.width, c.height, rng);
    total += expectRayMaskMatches(layer, c.p, std::to_string(c.width) + "x" + std::to_string(c.height));
    pixels += layer.objectId.size();
  }
  EXPECT_GT(total, 100u);
  EXPECT_LT(total, pixels / 2);
}

TEST_F(HybridRangeCheckTest, MaskListAndCountersMatchReferenceOnAdversarialLayers) {
  std::mt19937 rng(41);
  size_t total = 0;
  for (int round = 0; round < 5; ++round) {
    const MaskLayer layer = adversarialMaskLayer(43, 37, rng);
    for (const float velocityScale : {1.0f, 2.0f})
      total += expectRayMaskMatches(layer, parametersWith(0.9f, 40.0f, velocityScale),
                                    "round " + std::to_string(round) + " scale " + std::to_string(velocityScale));
  }
  EXPECT_GT(total, 100u);
}

// A range of several pixels meets a thin edge band far from the pixel: only a walk over every
// pixel of the range finds it. Object 2 (depth 1) moves 9 px right onto a deeper object 3
// whose left column alone is an edge; pixels up to 9 px left of it reach it.
TEST_F(HybridRangeCheckTest, LongRangesFindAnEdgeOnePixelWide) {
  const uint32_t width = 40, height = 5;
  const MaskLayer layer = slidingStep(width, height, {9.0f, 0.0f});
  const RayMaskParameters p = parametersWith(0.9f);
  const RayMaskReadback device = runRayMask(context(), layer, p);
  expectRayMaskMatches(layer, p, "long ranges");
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      // Edges: columns 18 and 19 (the step inside their window, ending on object 3).
      EXPECT_EQ(device.edges[y * width + x], x == 18 || x == 19 ? 1u : 0u) << x << "," << y;
      // Mask: every pixel whose range [x, x + 9] meets column 18 or 19, that is 9..19.
      EXPECT_EQ(device.mask[y * width + x], x >= 9 && x <= 19 ? 1u : 0u) << x << "," << y;
    }
}

// Only blocks with an edge within their tile's fastest reach are walked (list_range_blocks):
// object 2 (columns 0-19) moves 3 px right onto object 3, and the edge pixels lie at columns
// 18 and 19 (as in LongRangesFindAnEdgeOnePixelWide); blocks of columns 0-7 reach column 11 at most (3 px and a pixel of margin), so none of
// them is walked, and the mask is still the reference's, which walks every pixel. A tile whose
// speed was clamped to the tile size, or a curved path, has no such bound: every block of the
// moving tiles is walked.
TEST_F(HybridRangeCheckTest, BlocksWithNoEdgeWithinReachAreNotWalked) {
  const uint32_t width = 120, height = 40;
  const auto movingBlocks = [&](uint32_t tileSize) {
    // The tiles over columns 0-19 move; every 8 x 8 block of theirs.
    std::vector<uint32_t> out;
    for (uint32_t ty = 0; ty * tileSize < height; ++ty)
      for (uint32_t tx = 0; tx * tileSize < 20; ++tx)
        for (uint32_t oy = ty * tileSize; oy < std::min((ty + 1) * tileSize, height); oy += 8)
          for (uint32_t ox = tx * tileSize; ox < std::min((tx + 1) * tileSize, width); ox += 8)
            out.push_back(rangeBlockEntryOf(ox, oy, tileSize));
    std::sort(out.begin(), out.end());
    return out;
  };
  const MaskLayer slow = slidingStep(width, height, {3.0f, 0.0f});
  RayMaskParameters p = parametersWith(0.5f);
  expectRayMaskMatches(slow, p, "slow step");
  const RayMaskReadback device = runRayMask(context(), slow, p);
  for (uint32_t x = 0; x < width; ++x) {
    EXPECT_EQ(device.edges[x], x == 18 || x == 19 ? 1u : 0u) << x;
  }
  const std::vector<uint32_t> all = movingBlocks(p.blur.tileSize);
  EXPECT_LT(device.rangeBlocks.size(), all.size());
  EXPECT_GT(device.rangeBlocks.size(), 0u);
  for (const uint32_t entry : device.rangeBlocks)
    EXPECT_NE(gpu::rangeBlockOrigin(entry).x, 0u) << "block at row " << gpu::rangeBlockOrigin(entry).y;
  // A speed of 20 px is clamped to the 13-pixel tiles: every block is walked.
  const MaskLayer fast = slidingStep(width, height, {20.0f, 0.0f});
  expectRayMaskMatches(fast, p, "fast step");
  std::vector<uint32_t> walked = runRayMask(context(), fast, p).rangeBlocks;
  std::sort(walked.begin(), walked.end());
  EXPECT_EQ(walked, all);
  // Along curved paths likewise.
  MaskLayer curved = slow;
  const float none = std::numeric_limits<float>::quiet_NaN();
  curved.shutterPaths.assign(size_t(width) * height, mblur::packShutterPath(glm::vec2(none), glm::vec2(none)));
  p.blur.flags = HMB_GATHER_FLAG_ADAPTED_RANGE | HMB_GATHER_FLAG_CURVED_PATH;
  const RayMaskReadback curvedDevice = runRayMask(context(), curved, p);
  walked = curvedDevice.rangeBlocks;
  std::sort(walked.begin(), walked.end());
  EXPECT_EQ(walked, all);
  EXPECT_EQ(walked, rangeBlocks(curved, curvedDevice.edges, p));
  EXPECT_EQ(curvedDevice.mask, rangeCheck(curved, curvedDevice.edges, p));
}

// Along curved paths (random paths, adversarial records among them) each pixel walks its own
// path, for the mask and for the coverage selection, as the reference does; the paths change
// the mask.
TEST_F(HybridRangeCheckTest, CurvedPathsMatchTheReference) {
  size_t differ = 0;
  for (uint32_t round = 0; round < 3; ++round) {
    std::mt19937 rng(300 + round);
    const uint32_t width = 41 + 13 * round, height = 29 + 7 * round;
    MaskLayer layer = randomMaskLayer(width, height, rng);
    layer.shutterPaths = mblur::randomShutterPaths(layer.velocity, rng, 1.0f);
    RayMaskParameters p = parametersWith(0.5f);
    p.listOnlyUncovered = true;
    p.blur.samples = 5 + 4 * round;
    p.blur.seed = round;
    p.blur.flags = HMB_GATHER_FLAG_ADAPTED_RANGE | HMB_GATHER_FLAG_CURVED_PATH;
    const RayMaskReadback device = runRayMask(context(), layer, p);
    const std::vector<uint32_t> reference = rangeCheck(layer, device.edges, p);
    EXPECT_EQ(device.mask, reference) << round;
    const std::vector<bool> reveal = revealedPixels(layer, device.mask, p);
    for (uint32_t i = 0; i < device.mask.size(); ++i) {
      const uint32_t value = device.mask[i] == 0u ? HMB_MASK_NONE : (reveal[i] ? HMB_MASK_REVEALED : HMB_MASK_UNREVEALED);
      EXPECT_EQ(device.maskValues[i], value) << round << " pixel " << i;
    }
    const std::vector<uint32_t> straight = rangeCheck(layer.velocity, device.edges, width, height, p);
    for (size_t i = 0; i < straight.size(); ++i) differ += straight[i] != reference[i];
  }
  EXPECT_GT(differ, 0u) << "the paths should change the mask";
}

// A strongly curved path speeds up towards its end (|v + 2 s q| = 25 px per unit s where its
// reach |v| + |q| is 13): walked in steps of at most a pixel it meets an edge one pixel wide
// that 13 even steps would jump. Object 2 (depth 1) moves 1 px right onto object 3 (depth 5),
// so only its last column, 19, is an edge; pixel 7's path X + s (1, 0) + s^2 (12, 0) passes
// it, a straight walk over 13 even steps lands on 18.3 and 20.
TEST_F(HybridRangeCheckTest, CurvedPathsAreWalkedAPixelAStepWhereTheySpeedUp) {
  const uint32_t width = 40, height = 5, pathX = 7;
  MaskLayer layer = slidingStep(width, height, {1.0f, 0.0f});
  const float none = std::numeric_limits<float>::quiet_NaN();
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x)
      // p(t - uE) = X - u a - u^2 c with a = (1, 0), c = (12, 0): m = a / 2 + c / 4, o = a + c.
      layer.shutterPaths.push_back(x == pathX ? mblur::packShutterPath({3.5f, 0.0f}, {13.0f, 0.0f})
                                              : mblur::packShutterPath(glm::vec2(none), glm::vec2(none)));
  RayMaskParameters p = parametersWith(0.9f);
  p.blur.flags = HMB_GATHER_FLAG_ADAPTED_RANGE | HMB_GATHER_FLAG_CURVED_PATH;
  const RayMaskReadback device = runRayMask(context(), layer, p);
  EXPECT_EQ(device.mask, rangeCheck(layer, device.edges, p));
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      EXPECT_EQ(device.edges[y * width + x], x == 19 ? 1u : 0u) << x << "," << y;
      EXPECT_EQ(device.mask[y * width + x], x == pathX || (x >= 18 && x <= 19) ? 1u : 0u) << x << "," << y;
    }
}

// With the coverage composite, only the mask pixels whose composite samples meet the background
// are listed for the reveal (the others' background gets weight 0): the mask is unchanged, the
// list is the reference's selection, and the mask values say which pixels were listed.
TEST_F(HybridRangeCheckTest, OnlyPixelsWhoseCoverageMeetsTheBackgroundAreListed) {
  size_t listed = 0, unlisted = 0;
  for (uint32_t round = 0; round < 4; ++round) {
    const uint32_t width = 37 + 11 * round, height = 23 + 5 * round;
    auto [layer, p] = coverageCase(100 + round, width, height);
    p.blur.samples = 3 + 4 * round;
    p.blur.seed = round;
    const RayMaskReadback device = runRayMask(context(), layer, p);
    EXPECT_EQ(device.mask, rangeCheck(layer.velocity, device.edges, width, height, p)) << round;
    const std::vector<bool> reveal = revealedPixels(layer, device.mask, p);
    std::vector<uint32_t> expected;
    uint32_t maskPixels = 0;
    for (uint32_t i = 0; i < device.mask.size(); ++i) {
      maskPixels += device.mask[i];
      if (reveal[i]) expected.push_back(i);
      const uint32_t value = device.mask[i] == 0u ? HMB_MASK_NONE : (reveal[i] ? HMB_MASK_REVEALED : HMB_MASK_UNREVEALED);
      EXPECT_EQ(device.maskValues[i], value) << round << " pixel " << i;
    }
    std::vector<uint32_t> list = device.list;
    std::sort(list.begin(), list.end());
    EXPECT_EQ(list, expected) << round;
    EXPECT_EQ(device.counters.maskPixels, maskPixels) << round;
    // The others fill the list from its back, each once, for the composite.
    std::vector<uint32_t> unrevealed;
    for (uint32_t i = 0; i < device.mask.size(); ++i)
      if (device.mask[i] != 0u && !reveal[i]) unrevealed.push_back(i);
    std::vector<uint32_t> back = device.unrevealedList;
    std::sort(back.begin(), back.end());
    EXPECT_EQ(back, unrevealed) << round;
    expectDispatchFor(device.counters, expected.size(), "round " + std::to_string(round));
    listed += expected.size();
    unlisted += maskPixels - expected.size();
  }
  // Both kinds occur, so the test tells the selection from listing all or none.
  EXPECT_GT(listed, 20u);
  EXPECT_GT(unlisted, 20u);
}

// With the coverage composite the range check marks its mask pixels and list_range_mask lists
// them for the coverage test, a lane per walked block: every mask pixel once, each block's
// together and in row order (the order its reads want), whatever order the blocks take.
TEST_F(HybridRangeCheckTest, TheCoverageTestsListHoldsEachWalkedBlocksMaskPixelsTogetherInRowOrder) {
  size_t blocksWithMore = 0;
  for (uint32_t round = 0; round < 4; ++round) {
    const uint32_t width = 45 + 19 * round, height = 27 + 9 * round;
    auto [layer, p] = coverageCase(500 + round, width, height);
    p.blur.tileSize = 6 + 7 * round;  // 8 x 8 blocks cut short at tiles that are no multiple of 8
    const RayMaskReadback device = runRayMask(context(), layer, p);
    const std::vector<uint32_t> reference = rangeCheck(layer.velocity, device.edges, width, height, p);
    ASSERT_EQ(device.mask, reference) << round;
    // Each walked block's pixels, as the range check takes them (inside its tile and the image).
    std::vector<int64_t> blockOf(size_t(width) * height, -1);
    for (size_t b = 0; b < device.rangeBlocks.size(); ++b) {
      const uint32_t listed = device.rangeBlocks[b];
      const glm::uvec2 origin = gpu::rangeBlockOrigin(listed);
      const uint32_t tileSide = p.blur.tileSize;
      const uint32_t lastAcross = tileSide - (gpu::tileBlocksAcross(tileSide) - 1u) * HMB_MASK_TILE_GROUP_X;
      const uint32_t lastDown = tileSide - (gpu::tileBlocksDown(tileSide) - 1u) * HMB_MASK_TILE_GROUP_Y;
      const uint32_t across = (listed & HMB_RANGE_BLOCK_LAST_ACROSS) != 0u ? lastAcross : HMB_MASK_TILE_GROUP_X;
      const uint32_t down = (listed & HMB_RANGE_BLOCK_LAST_DOWN) != 0u ? lastDown : HMB_MASK_TILE_GROUP_Y;
      for (uint32_t y = origin.y; y < std::min(origin.y + down, height); ++y)
        for (uint32_t x = origin.x; x < std::min(origin.x + across, width); ++x) blockOf[size_t(y) * width + x] = int64_t(b);
    }
    std::vector<uint32_t> expected;
    for (uint32_t i = 0; i < reference.size(); ++i)
      if (reference[i] != 0u) {
        expected.push_back(i);
        EXPECT_GE(blockOf[i], 0) << round << ": mask pixel " << i << " in no walked block";
      }
    std::vector<uint32_t> listed = device.coverageList;
    std::vector<bool> finished(device.rangeBlocks.size(), false);
    for (size_t k = 0; k < listed.size(); ++k) {
      ASSERT_LT(listed[k], reference.size()) << round;
      const int64_t block = blockOf[listed[k]];
      ASSERT_GE(block, 0) << round << ": pixel " << listed[k] << " in no walked block";
      const bool continues = k > 0 && blockOf[listed[k - 1]] == block;
      if (continues) {
        EXPECT_GT(listed[k], listed[k - 1]) << round << ": block " << block << " out of row order";
        ++blocksWithMore;
      } else {
        EXPECT_FALSE(finished[size_t(block)]) << round << ": block " << block << " listed in two pieces";
        finished[size_t(block)] = true;
      }
    }
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, expected) << round;
    EXPECT_EQ(device.counters.coverageCount, expected.size()) << round;
  }
  EXPECT_GT(blocksWithMore, 20u) << "blocks with several mask pixels test the order";
}

TEST_F(HybridRangeCheckTest, StillLayerMasksNothingAndDispatchesNothing) {
  const uint32_t width = 33, height = 17;
  std::mt19937 rng(3);
  MaskLayer layer = randomMaskLayer(width, height, rng);
  layer.velocity.assign(layer.velocity.size(), glm::vec2(0.0f));
  layer.velocity[5] = glm::vec2(1e-31f, 0.0f);  // under 1e-30 px: still
  const RayMaskReadback device = runRayMask(context(), layer, parametersWith(0.0f));
  for (size_t i = 0; i < device.mask.size(); ++i) {
    EXPECT_EQ(device.edges[i], 0u);
    EXPECT_EQ(device.mask[i], 0u);
  }
  EXPECT_TRUE(device.list.empty());
  expectDispatchFor(device.counters, 0, "still");
  EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_MASK].x, 0u);
  EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_MASK].y, 0u);
}

// Long walks over many blocks: object 2 covers all but the last 20 columns of a 400 x 96
// image and moves 300 px right onto a deeper, still object 3, so every listed block's pixels
// walk up to 300 px (a coarse walk, and a fine one where the edge lies within reach). One
// group wanted would take every block, about 300 loop rounds a pixel each, far past the
// 65535 llvmpipe 22.3 allows an invocation (it ends the loops silently: pixels left out of the
// mask): its run is cut to what the budget holds, and the mask is the reference's. A driver
// without a budget takes the one group.
TEST_F(HybridRangeCheckTest, LongWalksCutTheRunsToTheLoopBudget) {
  const uint32_t width = 400, height = 96;
  const MaskLayer layer = movingOntoStillColumns(width, height, 20, {300.0f, 0.0f});
  RayMaskParameters p = parametersWith(0.9f, 400.0f);
  p.rangeCheckGroups = 1u;
  const size_t masked = expectRayMaskMatchesIn(layer, p, "long walks, one group wanted");
  EXPECT_GT(masked, size_t(300) * height);
  const RayMaskReadback device = runRayMask(context(), layer, p);
  EXPECT_GT(device.counters.rangeBlockCount * 300u, 65535u) << "one run would pass the budget";
  if (context().profile().loopBudget)
    EXPECT_GT(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_RANGE_CHECK].x, 1u);
  else
    EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_RANGE_CHECK].x, 1u);
}

// One 1024-px tile over a 1024 x 1024 image: object 2 (depth 1) moving `speed` px right, and
// a still, deeper object 3 in a 40-px square near the bottom, where the edges are. The tile's
// 16,384 blocks are tested a lane each, each over at most 16 x 16 coarse blocks: a reach of 25
// or 12 px is tested and most blocks are left out; a reach of 70 px (over 16 coarse blocks) is
// listed untested. (When a 64-lane group took a tile, a lane had 256 of these blocks: tested
// over 16 x 16 coarse blocks, near 75,000 loop rounds, past the 65535 llvmpipe 22.3 allows an
// invocation, which ends the loops silently and left a lane's last blocks unlisted.)
TEST_F(HybridRangeCheckTest, ALargeTileIsTestedABlockALane) {
  const uint32_t side = 1024;
  const size_t tileBlocks = (side / 8) * (side / 8);
  for (const float speed : {25.0f, 12.0f, 70.0f}) {
    MaskLayer layer{side, side, {}, {}, {}};
    for (uint32_t y = 0; y < side; ++y)
      for (uint32_t x = 0; x < side; ++x) {
        const bool behind = x >= 500 && x < 540 && y >= 960 && y < 1000;
        layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, behind ? 5.0f : 1.0f);
        layer.velocity.emplace_back(behind ? glm::vec2(0.0f) : glm::vec2(speed, 0.0f));
        layer.objectId.push_back(behind ? 3u : 2u);
      }
    RayMaskParameters p = parametersWith(0.5f);
    p.blur.tileSize = side;
    p.rangeCheckGroups = 0u;
    const std::string what = "a 1024-px tile, speed " + std::to_string(speed);
    EXPECT_GT(expectRayMaskMatchesIn(layer, p, what), 500u) << what;
    const size_t listed = runRayMask(context(), layer, p).rangeBlocks.size();
    if (speed > 60.0f)
      EXPECT_GT(listed, tileBlocks * 9 / 10) << what << ": a reach wider than the test is listed untested";
    else
      EXPECT_LT(listed, tileBlocks / 10) << what;
  }
}

// A row whose first n pixels each move 1 px right onto the next, deeper, object: each is an
// edge (threshold 0; the depth ramp is in every window) and the mask is exactly those n. The
// counts around multiples of 64 size the dispatch.
MaskLayer rampRow(uint32_t n) {
  MaskLayer layer{n + 1, 1, {}, {}, {}};
  for (uint32_t x = 0; x <= n; ++x) {
    layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, 1.0f + 0.1f * float(x));
    layer.velocity.emplace_back(x < n ? glm::vec2(1.0f, 0.0f) : glm::vec2(0.0f));
    layer.objectId.push_back(x + 1);
  }
  return layer;
}

TEST_F(HybridRangeCheckTest, DispatchIsTheCountInGroupsOf64) {
  for (const uint32_t n : {1u, 63u, 64u, 65u, 128u, 129u, 1000u}) {
    const MaskLayer layer = rampRow(n);
    EXPECT_EQ(expectRayMaskMatches(layer, parametersWith(0.0f), "n " + std::to_string(n)), n);
    const gpu::RayMaskCounters counters = runRayMask(context(), layer, parametersWith(0.0f)).counters;
    EXPECT_EQ(counters.dispatches[HMB_RAY_MASK_DISPATCH_MASK].x, (n + 63) / 64) << n;
  }
}

// Over 65535 * 64 masked pixels: the groups fold into a second row. Every column of a ramp
// image but the last moves 1 px right onto the next, deeper, object.
TEST_F(HybridRangeCheckTest, LongListFoldsIntoASecondRowOfGroups) {
  const uint32_t width = 2100, height = 2048;
  MaskLayer layer{width, height, {}, {}, {}};
  const size_t pixels = size_t(width) * height;
  layer.normalDepth.reserve(pixels);
  layer.velocity.reserve(pixels);
  layer.objectId.reserve(pixels);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, 1.0f + 0.1f * float(x));
      layer.velocity.emplace_back(x + 1 < width ? glm::vec2(1.0f, 0.0f) : glm::vec2(0.0f));
      layer.objectId.push_back(x + 1);
    }
  RayMaskParameters p = parametersWith(0.0f);
  // One group wanted: its run would pass HMB_RANGE_CHECK_MAX_RUN blocks, so there are more.
  p.rangeCheckGroups = 1u;
  const RayMaskReadback device = runRayMask(context(), layer, p);
  const uint64_t expected = uint64_t(width - 1) * height;
  ASSERT_GT(expected, 65535u * 64u);
  ASSERT_GT(device.counters.rangeBlockCount, HMB_RANGE_CHECK_MAX_RUN);
  expectRangeDispatchFor(device, device.counters.rangeBlockCount, p, "folded");
  EXPECT_GT(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_RANGE_CHECK].x, 1u);
  expectDispatchFor(device.counters, expected, "folded");
  EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_MASK].x, 65535u);
  EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_MASK].y, 2u);
  std::vector<uint32_t> list = device.list;
  std::sort(list.begin(), list.end());
  EXPECT_EQ(std::adjacent_find(list.begin(), list.end()), list.end()) << "a pixel listed twice";
  for (const uint32_t index : list) {
    if (index % width == width - 1) {
      ADD_FAILURE() << "still pixel " << index << " listed";
      break;
    }
  }
}

}  // namespace
}  // namespace hmb::test
