// tile_max.comp against the reference: random velocities at odd sizes and tile sizes, partial
// border tiles, non-finite and huge velocities, and the tie rule.
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/mblur/mblur_harness.h"
#include "tests/mblur/mblur_reference.h"
#include "tests/support/vulkan_precision.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace mblur;

// Mostly a few pixels per frame, some sub-pixel, some far beyond any tile.
std::vector<glm::vec2> randomVelocities(size_t count, std::mt19937& rng) {
  std::uniform_real_distribution<float> small(-6.0f, 6.0f), tiny(-0.3f, 0.3f), huge(-5000.0f, 5000.0f);
  std::uniform_int_distribution<int> kind(0, 9);
  std::vector<glm::vec2> v(count);
  for (glm::vec2& q : v) {
    const int k = kind(rng);
    q = k < 6 ? glm::vec2(small(rng), small(rng)) : k < 8 ? glm::vec2(tiny(rng), tiny(rng)) : glm::vec2(huge(rng), huge(rng));
  }
  return v;
}

bool close(glm::vec4 a, glm::vec4 b) {
  for (int i = 0; i < 3; ++i)
    if (!(std::abs(a[i] - b[i]) <= 1e-5f * (1.0f + std::abs(b[i])))) return false;
  return a.w == 0.0f;
}

// Every tile equals the reference (to rounding). A tile may differ only on a near tie: the
// device's speed within rounding of the reference's and its velocity one of the tile's own.
void expectTilesMatch(const std::vector<glm::vec2>& velocity, uint32_t width, uint32_t height, uint32_t tileSize,
                      float scale) {
  const auto device = runTileMax(VulkanTest::context(), velocity, width, height, tileSize, scale);
  const auto reference = tileMax(velocity, width, height, tileSize, scale);
  ASSERT_EQ(device.size(), reference.size());
  const passes::TileGrid grid = passes::tileGridFor(width, height, tileSize);
  size_t nearTies = 0;
  for (uint32_t t = 0; t < grid.count(); ++t) {
    if (close(device[t], reference[t])) continue;
    ASSERT_NEAR(device[t].z, reference[t].z, 1e-5f * (1.0f + reference[t].z))
        << "tile " << t << " of " << width << "x" << height << " m " << tileSize;
    bool ownVelocity = false;
    const uint32_t tx = t % grid.x, ty = t / grid.x;
    for (uint32_t y = ty * tileSize; y < std::min((ty + 1) * tileSize, height); ++y)
      for (uint32_t x = tx * tileSize; x < std::min((tx + 1) * tileSize, width); ++x) {
        float speed;
        const glm::vec2 v = gatherVelocity(velocity[y * width + x], scale, float(tileSize), speed);
        ownVelocity |= close(device[t], glm::vec4(v, speed, 0.0f));
      }
    EXPECT_TRUE(ownVelocity) << "tile " << t << ": " << device[t].x << ", " << device[t].y;
    ++nearTies;
  }
  EXPECT_LE(nearTies, grid.count() / 100 + 1) << "too many tiles decided by rounding";
}

using MblurTileMaxTest = VulkanTest;

TEST_F(MblurTileMaxTest, RandomVelocitiesMatchTheReferenceAtOddSizes) {
  std::mt19937 rng(7);
  const std::pair<uint32_t, uint32_t> sizes[] = {{1, 1}, {3, 5}, {7, 3}, {97, 61}};
  for (auto [width, height] : sizes)
    for (uint32_t tileSize : {1u, 3u, 8u, 40u})
      for (float scale : {2.0f, 1.0f}) {  // adapted at E = 1/60, 120 fps; centred
        SCOPED_TRACE(testing::Message() << width << "x" << height << " m " << tileSize << " scale " << scale);
        expectTilesMatch(randomVelocities(size_t(width) * height, rng), width, height, tileSize, scale);
      }
}

TEST_F(MblurTileMaxTest, PartialBorderTilesAtAHdLikeSize) {
  std::mt19937 rng(11);
  const uint32_t width = 1279, height = 719;
  expectTilesMatch(randomVelocities(size_t(width) * height, rng), width, height, 40, 2.0f);
}

TEST_F(MblurTileMaxTest, TheLargestTileSizeCoversItsWholeTile) {
  // 1024 px tiles: each lane strides over 128 x 128 pixels; a lone fast pixel in the far corner
  // of the first tile must still win.
  const uint32_t width = 1030, height = 1025;
  std::vector<glm::vec2> velocity(size_t(width) * height, glm::vec2(0.25f, 0.0f));
  velocity[size_t(1023) * width + 1023] = {3.0f, -4.0f};
  velocity[size_t(1024) * width + 1029] = {0.0f, 1.0f};
  const auto device = runTileMax(context(), velocity, width, height, 1024, 1.0f);
  ASSERT_EQ(device.size(), 4u);
  EXPECT_EQ(device[0], glm::vec4(3.0f, -4.0f, 5.0f, 0.0f));
  EXPECT_EQ(device[1], glm::vec4(0.25f, 0.0f, 0.25f, 0.0f));
  EXPECT_EQ(device[2], glm::vec4(0.25f, 0.0f, 0.25f, 0.0f));
  EXPECT_EQ(device[3], glm::vec4(0.0f, 1.0f, 1.0f, 0.0f));
}

TEST_F(MblurTileMaxTest, NonFiniteVelocitiesCountAsZeroAndHugeOnesClampToTheTile) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const uint32_t width = 12, height = 4, tileSize = 4;  // three tiles in a row
  std::vector<glm::vec2> velocity(size_t(width) * height, glm::vec2(0.0f));
  auto at = [&](uint32_t x, uint32_t y) -> glm::vec2& { return velocity[y * width + x]; };
  // Tile 0: only non-finite velocities.
  at(0, 0) = {nan, 1.0f};
  at(1, 1) = {inf, 0.0f};
  at(2, 2) = {-inf, nan};
  at(3, 3) = {1.0f, inf};
  // Tile 1: non-finite beside a small finite one.
  at(4, 0) = {nan, nan};
  at(6, 2) = {0.5f, -0.25f};
  // Tile 2: 1e30 and -1e30 px per frame, and one that overflows when scaled.
  at(8, 0) = {1e30f, 2e30f};
  at(9, 1) = {-1e30f, 0.0f};
  at(10, 2) = {3e38f, 3e38f};
  const auto device = runTileMax(context(), velocity, width, height, tileSize, 2.0f);
  ASSERT_EQ(device.size(), 3u);
  EXPECT_EQ(device[0], glm::vec4(0.0f));
  EXPECT_EQ(glm::vec2(device[1]), glm::vec2(1.0f, -0.5f));
  // The speed is a square root: Vulkan's rule for sqrt (vulkan_precision.h) bounds it.
  EXPECT_LE(ulpDistance(device[1].z, std::sqrt(1.25f)), kVulkanSqrtUlp) << device[1].z;
  EXPECT_EQ(device[1].w, 0.0f);
  // Both huge velocities clamp to exactly the tile size; the first in row-major order wins.
  EXPECT_EQ(device[2].z, 4.0f);
  EXPECT_NEAR(device[2].x, 4.0f / std::sqrt(5.0f), 1e-6f);
  EXPECT_NEAR(device[2].y, 8.0f / std::sqrt(5.0f), 1e-6f);
  for (size_t t = 0; t < device.size(); ++t) EXPECT_TRUE(close(device[t], tileMax(velocity, width, height, tileSize, 2.0f)[t]));
}

TEST_F(MblurTileMaxTest, TiesGoToTheFirstPixelInRowMajorOrder) {
  const uint32_t width = 8, height = 8, tileSize = 8;
  // Equal speeds (exactly 5 in float) in different directions, scattered over the tile.
  std::vector<glm::vec2> velocity(size_t(width) * height, glm::vec2(1.0f, 0.0f));
  velocity[5 * width + 1] = {3.0f, 4.0f};
  velocity[2 * width + 6] = {-4.0f, 3.0f};  // first in row-major order
  velocity[2 * width + 7] = {0.0f, 5.0f};
  velocity[7 * width + 0] = {5.0f, 0.0f};
  for (int run = 0; run < 3; ++run) {
    const auto device = runTileMax(context(), velocity, width, height, tileSize, 1.0f);
    ASSERT_EQ(device.size(), 1u);
    EXPECT_EQ(device[0], glm::vec4(-4.0f, 3.0f, 5.0f, 0.0f));
  }
  // Clamped velocities tie at exactly the tile size, whatever their unclamped lengths.
  std::vector<glm::vec2> fast(size_t(width) * height, glm::vec2(0.0f));
  fast[6 * width + 3] = {1e6f, 0.0f};
  fast[3 * width + 5] = {0.0f, -100.0f};  // first
  fast[3 * width + 6] = {-1e20f, 1e20f};
  const auto clamped = runTileMax(context(), fast, width, height, tileSize, 1.0f);
  EXPECT_EQ(clamped[0], glm::vec4(0.0f, -8.0f, 8.0f, 0.0f));
}

}  // namespace
}  // namespace hmb::test
