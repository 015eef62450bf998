// gather_jimenez.comp (Jimenez 2014) against the reference on random and adversarial layers;
// still images unchanged; and, with the tile jitter off, the centred blur of a moving edge over
// a still background, where the filter's weights give the exact coverage.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/mblur/mblur_harness.h"
#include "tests/mblur/mblur_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace mblur;
using passes::PostProcessFilter;
using passes::PostProcessSettings;

PostProcessSettings jimenezSettings(uint32_t tileSize, uint32_t samples = 15) {
  PostProcessSettings s;
  s.filter = PostProcessFilter::Jimenez;
  s.tileSize = tileSize;
  s.samples = samples;
  s.seed = 3;
  s.softZExtent = 0.05f;
  return s;
}

// As for the McGuire gather: within 2e-4 of the reference but for at most 0.5% of the pixels,
// where a sample position rounds to the neighbouring pixel on the device.
void expectJimenezMatches(const Layer& layer, const PostProcessSettings& s) {
  const auto tiles = referenceTiles(layer, s);
  expectMatchesReference(runJimenezGather(VulkanTest::context(), layer, tiles, s), gatherJimenez(layer, tiles, s));
}

using MblurJimenezTest = VulkanTest;

TEST_F(MblurJimenezTest, RandomLayersMatchTheReference) {
  std::mt19937 rng(31);
  const std::pair<uint32_t, uint32_t> sizes[] = {{1, 1}, {3, 5}, {97, 61}};
  for (auto [width, height] : sizes)
    for (uint32_t tileSize : {8u, 20u})
      for (uint32_t samples : {1u, 15u, 32u}) {
        SCOPED_TRACE(testing::Message() << width << "x" << height << " m " << tileSize << " S " << samples);
        expectJimenezMatches(randomLayer(width, height, rng), jimenezSettings(tileSize, samples));
      }
}

TEST_F(MblurJimenezTest, AdversarialInputsStayFiniteAndMatchTheReference) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::mt19937 rng(13);
  Layer layer = randomLayer(37, 29, rng);
  const float depths[] = {1e-6f, 1e30f, 1e-6f, 1.0f, 1.0f, nan, inf, -1.0f};
  const glm::vec2 velocities[] = {{1e30f, -1e30f}, {nan, 0.0f}, {0.0f, inf}, {0.2f, 0.1f}, {0.0f, 0.0f}, {-1e30f, 3.0f}};
  const float colors[] = {nan, inf, -inf, 1e30f, -2.0f};
  std::uniform_int_distribution<size_t> pick(0, 1000);
  for (size_t i = 0; i < layer.color.size(); ++i) {
    if (pick(rng) % 3 == 0) layer.normalDepth[i].w = depths[pick(rng) % std::size(depths)];
    if (pick(rng) % 3 == 0) layer.velocity[i] = velocities[pick(rng) % std::size(velocities)];
    if (pick(rng) % 5 == 0) layer.color[i][pick(rng) % 4] = colors[pick(rng) % std::size(colors)];
  }
  PostProcessSettings s = jimenezSettings(6);
  expectJimenezMatches(layer, s);
  s.softZExtent = 1e-30f;
  expectJimenezMatches(layer, s);
}

TEST_F(MblurJimenezTest, StillImagesAreUnchanged) {
  std::mt19937 rng(1);
  Layer layer = randomLayer(29, 19, rng);
  for (glm::vec2& v : layer.velocity) v = glm::vec2(0.0f);
  const PostProcessSettings s = jimenezSettings(8);
  const auto out = runJimenezGather(context(), layer, referenceTiles(layer, s), s);
  const Layer held = stored(layer);  // the colours as the G-buffer holds them
  for (size_t i = 0; i < out.size(); ++i) ASSERT_EQ(out[i], sanitizeColor(held.color[i])) << i;
}

TEST_F(MblurJimenezTest, CentredBlurOfAMovingEdgeHasTheRightCoverage) {
  // A wide bar moving +x at 2r = 16 px per exposure (centred radius r = 8) in front of a still
  // background. Centred truth at distance d from the bar's right edge: the bar covers the pixel
  // for (r - d) / 2r outside (d > 0) and (r + |d|) / 2r inside, clamped to [0, 1].
  const uint32_t width = 96, height = 8;
  Layer layer = stillLayer(width, height);
  const float r = 8.0f, edge = 60.0f;
  PostProcessSettings s = jimenezSettings(16, 32);
  s.jimenezTileJitter = 0.0f;  // one dominant velocity for every pixel near the edge
  const glm::vec2 q(2.0f * r / (s.exposure * s.fps), 0.0f);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const size_t i = size_t(y) * width + x;
      const bool bar = x + 0.5f < edge && x >= 20;
      layer.color[i] = bar ? glm::vec4(1.0f, 0.0f, 0.0f, 1.0f) : glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
      layer.normalDepth[i].w = bar ? 2.0f : 10.0f;
      layer.velocity[i] = bar ? q : glm::vec2(0.0f);
    }
  const auto out = runStage(context(), layer, s);
  for (uint32_t x = 44; x < 76; ++x) {
    const float d = x + 0.5f - edge;
    const float coverage = std::clamp((r - d) / (2.0f * r), 0.0f, 1.0f);
    // 16 pairs of nearest-pixel samples: coverage steps of 1/32 plus a pixel of rounding.
    EXPECT_NEAR(out[4 * width + x].x, coverage, 0.1f) << "x " << x;
    EXPECT_NEAR(out[4 * width + x].x + out[4 * width + x].z, 1.0f, 1e-5f) << "x " << x;
  }
}

}  // namespace
}  // namespace hmb::test
