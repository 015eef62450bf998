// gather.comp (McGuire 2012 with the paper's appendix weights) against the reference in both
// ranges, on random layers and adversarial ones; the weight functions against the appendix's
// definitions; still images left unchanged; seeds (the mask boosts: tests/hybrid/composite_test.cpp).
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "tests/mblur/mblur_harness.h"
#include "tests/mblur/mblur_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace mblur;
using passes::GatherRange;
using passes::PostProcessSettings;

PostProcessSettings settingsFor(GatherRange range, uint32_t tileSize, uint32_t samples = 15, uint32_t seed = 1) {
  PostProcessSettings s;
  s.range = range;
  s.tileSize = tileSize;
  s.samples = samples;
  s.seed = seed;
  s.softZExtent = 0.05f;
  return s;
}

void expectGatherMatches(const Layer& layer, const PostProcessSettings& s) {
  const auto tiles = referenceTiles(layer, s);
  expectMatchesReference(runGather(VulkanTest::context(), layer, tiles, s), gather(layer, tiles, nullptr, s));
}

TEST(MblurWeightsTest, AppendixWeightsFollowTheirDefinitions) {
  auto smoothstep = [](double e0, double e1, double x) {
    const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
  };
  for (float v : {0.3f, 1.0f, 7.5f, 40.0f})
    for (float s = 0.0f; s < 2.0f * v; s += v / 64.0f) {
      EXPECT_NEAR(cylinder(v, s), 1.0 - smoothstep(0.95 * v, 1.05 * v, s), 1e-5) << v << " " << s;
      EXPECT_NEAR(cone(s, v), std::clamp(1.0 - s / v, 0.0, 1.0), 1e-6);
    }
  // Zero speed: reaches only its own pixel.
  EXPECT_EQ(cylinder(0.0f, 0.0f), 1.0f);
  EXPECT_EQ(cylinder(0.0f, 1.0f), 0.0f);
  EXPECT_EQ(cone(0.0f, 0.0f), 1.0f);
  EXPECT_EQ(cone(1.0f, 0.0f), 0.0f);

  const float soft = 0.1f;
  // Sample well in front of the target (z >= 1): foreground only, by the sample's speed.
  AppendixWeights w = appendixWeights(5.0f, 1.0f, 10.0f, 8.0f, 2.0f, soft);
  EXPECT_FLOAT_EQ(w.foreground, 1.0f - 2.0f / 8.0f);
  EXPECT_EQ(w.background, 0.0f);
  EXPECT_EQ(w.simultaneous, 2.0f);
  // Sample well behind: background only, by the target's speed.
  w = appendixWeights(1.0f, 5.0f, 10.0f, 8.0f, 2.0f, soft);
  EXPECT_EQ(w.foreground, 0.0f);
  EXPECT_FLOAT_EQ(w.background, 1.0f - 2.0f / 10.0f);
  // Equal depths: both sides, and w_s vanishes past the slower one's reach.
  w = appendixWeights(3.0f, 3.0f, 10.0f, 4.0f, 5.0f, soft);
  EXPECT_EQ(w.foreground, 0.0f);
  EXPECT_FLOAT_EQ(w.background, 0.5f);
  EXPECT_EQ(w.simultaneous, 0.0f);
  // Half SOFT_Z_EXTENT apart (z = 0.5): the foreground ramp saturates, the background one is half.
  w = appendixWeights(3.05f, 3.0f, 10.0f, 10.0f, 0.0f, soft);
  EXPECT_EQ(w.foreground, 1.0f);
  EXPECT_NEAR(w.background, 0.5f, 1e-5f);
}

using MblurGatherTest = VulkanTest;

TEST_F(MblurGatherTest, RandomLayersMatchTheReferenceInBothRanges) {
  std::mt19937 rng(21);
  const std::pair<uint32_t, uint32_t> sizes[] = {{1, 1}, {3, 5}, {97, 61}};
  for (auto [width, height] : sizes)
    for (GatherRange range : {GatherRange::Centered, GatherRange::Adapted})
      for (uint32_t tileSize : {8u, 40u}) {
        SCOPED_TRACE(testing::Message() << width << "x" << height << " " << passes::rangeName(range) << " m " << tileSize);
        expectGatherMatches(randomLayer(width, height, rng), settingsFor(range, tileSize));
      }
}

TEST_F(MblurGatherTest, SampleCountsFromOneToTheLargest) {
  std::mt19937 rng(5);
  const Layer layer = randomLayer(41, 23, rng);
  for (GatherRange range : {GatherRange::Centered, GatherRange::Adapted})
    for (uint32_t samples : {1u, 2u, 4u, 255u}) {
      SCOPED_TRACE(testing::Message() << passes::rangeName(range) << " S " << samples);
      expectGatherMatches(layer, settingsFor(range, 8, samples));
    }
}

TEST_F(MblurGatherTest, AdversarialInputsStayFiniteAndMatchTheReference) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::mt19937 rng(9);
  const uint32_t width = 37, height = 29;
  Layer layer = randomLayer(width, height, rng);
  const float depths[] = {1e-6f, 1e30f, 1e-6f, 1.0f, 1.0f, nan, inf, -1.0f, 0.0f};
  const glm::vec2 velocities[] = {{1e30f, -1e30f}, {nan, 0.0f}, {0.0f, inf}, {0.2f, 0.1f}, {0.0f, 0.0f},
                                  {-1e30f, 3.0f},  {40.0f, 0.0f}, {-inf, -inf}};
  const float colors[] = {nan, inf, -inf, 1e30f, -2.0f, 0.25f};
  std::uniform_int_distribution<size_t> pick(0, 1000);
  for (size_t i = 0; i < layer.color.size(); ++i) {
    if (pick(rng) % 3 == 0) layer.normalDepth[i].w = depths[pick(rng) % std::size(depths)];
    if (pick(rng) % 3 == 0) layer.velocity[i] = velocities[pick(rng) % std::size(velocities)];
    if (pick(rng) % 5 == 0) layer.color[i][pick(rng) % 4] = colors[pick(rng) % std::size(colors)];
  }
  for (GatherRange range : {GatherRange::Centered, GatherRange::Adapted}) {
    SCOPED_TRACE(passes::rangeName(range));
    PostProcessSettings s = settingsFor(range, 6);
    expectGatherMatches(layer, s);
    s.softZExtent = 1e-30f;  // every depth difference saturates
    expectGatherMatches(layer, s);
  }
}

// The boost that falls with the tile's speed (max(1, k / |v_N|), the hybrid's default) against
// the reference, at a k below the fastest tiles' speed (those keep 1) and one above the tile
// size (every tile boosted); it must change the image from the constant boost's.
TEST_F(MblurGatherTest, ABoostThatFallsWithTheSpeedMatchesTheReference) {
  std::mt19937 rng(44);
  const Layer layer = randomLayer(73, 41, rng);
  for (GatherRange range : {GatherRange::Centered, GatherRange::Adapted})
    for (const float pixels : {24.0f, 80.0f}) {
      SCOPED_TRACE(testing::Message() << passes::rangeName(range) << " k " << pixels);
      PostProcessSettings s = settingsFor(range, 40);
      const auto tiles = referenceTiles(layer, s);
      const std::vector<glm::vec4> constant = gather(layer, tiles, nullptr, s);
      s.foregroundBoostPixels = pixels;
      const std::vector<glm::vec4> falling = gather(layer, tiles, nullptr, s);
      EXPECT_NE(falling, constant);
      expectMatchesReference(runGather(VulkanTest::context(), layer, tiles, s), falling);
    }
}

// The gather runs over the 8 x 8 blocks that touch a moving tile and copies the others
// (list_gather_blocks, copy_still_blocks): with tiles still at random, at the threshold and just
// under it, every pixel must still be the reference's (the output starts as NaN, so a block in
// neither list fails). Tile sizes under, at and over the block's, images of ragged blocks, and
// more than 256 blocks of a kind (the lists' dispatches fold into rows).
TEST_F(MblurGatherTest, StillAndMovingBlocksEachMatchTheReference) {
  std::mt19937 rng(61);
  const struct {
    uint32_t width, height, tileSize;
  } cases[] = {{1, 1, 1}, {9, 7, 3}, {97, 61, 8}, {200, 100, 13}, {203, 130, 40}, {300, 170, 5}};
  for (const auto& c : cases) {
    SCOPED_TRACE(testing::Message() << c.width << "x" << c.height << " m " << c.tileSize);
    const Layer layer = randomLayer(c.width, c.height, rng);
    for (GatherRange range : {GatherRange::Centered, GatherRange::Adapted}) {
      const PostProcessSettings s = settingsFor(range, c.tileSize);
      std::vector<glm::vec4> tiles = referenceTiles(layer, s);
      std::uniform_int_distribution<int> pick(0, 3);
      size_t still = 0;
      for (glm::vec4& tile : tiles) {
        const int kind = pick(rng);
        if (kind == 0) tile = glm::vec4(0.0f);
        if (kind == 1) tile = glm::vec4(0.3f, 0.0f, std::nextafter(gpu::kMinBlurPixels, 0.0f), 0.0f);
        if (kind == 2) tile = glm::vec4(0.0f, -gpu::kMinBlurPixels, gpu::kMinBlurPixels, 0.0f);
        still += kind < 2;
      }
      if (tiles.size() > 4) {
        ASSERT_GT(still, 0u);
      }
      expectMatchesReference(runGather(context(), layer, tiles, s), gather(layer, tiles, nullptr, s));
    }
  }
}

PostProcessSettings curvedSettings(uint32_t tileSize, uint32_t samples = 15) {
  PostProcessSettings s = settingsFor(GatherRange::Adapted, tileSize, samples);
  s.motionPath = passes::MotionPath::Curved;
  return s;
}

TEST_F(MblurGatherTest, CurvedPathsMatchTheReference) {
  std::mt19937 rng(33);
  const std::pair<uint32_t, uint32_t> sizes[] = {{1, 1}, {3, 5}, {97, 61}};
  for (auto [width, height] : sizes)
    for (uint32_t tileSize : {8u, 40u}) {
      SCOPED_TRACE(testing::Message() << width << "x" << height << " m " << tileSize);
      Layer layer = randomLayer(width, height, rng);
      const PostProcessSettings s = curvedSettings(tileSize);
      layer.shutterPaths = randomShutterPaths(layer.velocity, rng, s.exposure * s.fps);
      expectGatherMatches(layer, s);
      if (width * height < 100) continue;
      // The paths change the image: the curved gather is not the straight one. The straight
      // gather, a kernel built without the curved path's code, still matches its reference with
      // the paths present.
      PostProcessSettings linear = s;
      linear.motionPath = passes::MotionPath::Linear;
      const auto tiles = referenceTiles(layer, s);
      const auto curved = runGather(context(), layer, tiles, s), straight = runGather(context(), layer, tiles, linear);
      expectMatchesReference(straight, gather(layer, tiles, nullptr, linear));
      size_t differ = 0;
      for (size_t i = 0; i < curved.size(); ++i) differ += maxAbsDifference(curved[i], straight[i]) > 1e-3f;
      EXPECT_GT(differ, curved.size() / 10);
    }
}

// The adversarial layer of the straight gather, with adversarial paths: still finite and equal
// to the reference, also with every record "no path"; with no paths buffer at all the curved
// setting is refused.
TEST_F(MblurGatherTest, CurvedPathsOnAdversarialInputsStayFiniteAndMatchTheReference) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::mt19937 rng(17);
  Layer layer = randomLayer(37, 29, rng);
  const float depths[] = {1e-6f, 1e30f, 1.0f, nan, inf, -1.0f, 0.0f};
  const glm::vec2 velocities[] = {{1e30f, -1e30f}, {nan, 0.0f}, {0.0f, inf}, {0.2f, 0.1f}, {40.0f, 0.0f}};
  std::uniform_int_distribution<size_t> pick(0, 1000);
  for (size_t i = 0; i < layer.color.size(); ++i) {
    if (pick(rng) % 3 == 0) layer.normalDepth[i].w = depths[pick(rng) % std::size(depths)];
    if (pick(rng) % 3 == 0) layer.velocity[i] = velocities[pick(rng) % std::size(velocities)];
  }
  PostProcessSettings s = curvedSettings(6);
  const Layer straight = layer;
  layer.shutterPaths = randomShutterPaths(layer.velocity, rng, s.exposure * s.fps);
  expectGatherMatches(layer, s);
  s.softZExtent = 1e-30f;
  expectGatherMatches(layer, s);
  Layer pathless = straight;
  const glm::vec2 none(nan);
  pathless.shutterPaths.assign(pathless.color.size(), packShutterPath(none, none));
  expectGatherMatches(pathless, s);
  EXPECT_THROW(runGather(context(), straight, referenceTiles(straight, s), s), Error);
}

TEST_F(MblurGatherTest, StillAndSubPixelMotionLeaveTheImageUnchanged) {
  std::mt19937 rng(2);
  Layer layer = randomLayer(23, 17, rng);
  for (glm::vec2& v : layer.velocity) v = glm::vec2(0.0f);
  layer.color[5] = {std::numeric_limits<float>::quiet_NaN(), 1e30f, 0.5f, 1.0f};
  for (GatherRange range : {GatherRange::Centered, GatherRange::Adapted}) {
    const PostProcessSettings s = settingsFor(range, 5);
    const auto still = runGather(context(), layer, referenceTiles(layer, s), s);
    // The colours as the G-buffer holds them (mblur_reference.h, stored).
    const Layer held = stored(layer);
    for (size_t i = 0; i < still.size(); ++i) ASSERT_EQ(still[i], sanitizeColor(held.color[i])) << i;
    // Under half a pixel of blur everywhere (0.2 px/frame * E * fps = 0.4 px): the early out.
    Layer slow = layer;
    for (glm::vec2& v : slow.velocity) v = glm::vec2(0.2f, 0.0f);
    const auto subPixel = runGather(context(), slow, referenceTiles(slow, s), s);
    for (size_t i = 0; i < subPixel.size(); ++i) ASSERT_EQ(subPixel[i], sanitizeColor(held.color[i])) << i;
  }
}

TEST_F(MblurGatherTest, TheSeedDecidesTheJitterAndNothingElse) {
  std::mt19937 rng(8);
  const Layer layer = randomLayer(61, 37, rng);
  const PostProcessSettings a = settingsFor(GatherRange::Adapted, 8, 15, 1), b = settingsFor(GatherRange::Adapted, 8, 15, 2);
  const auto tiles = referenceTiles(layer, a);
  const auto first = runGather(context(), layer, tiles, a);
  EXPECT_EQ(runGather(context(), layer, tiles, a), first) << "same seed, different result";
  const auto other = runGather(context(), layer, tiles, b);
  size_t differ = 0;
  for (size_t i = 0; i < first.size(); ++i) differ += first[i] != other[i];
  EXPECT_GT(differ, first.size() / 4);
  expectMatchesReference(other, gather(layer, tiles, nullptr, b));
}

}  // namespace
}  // namespace hmb::test
