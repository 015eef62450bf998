// neighbor_max.comp against the reference: random tile grids, border clamping, ties.
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "tests/mblur/mblur_harness.h"
#include "tests/mblur/mblur_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace mblur;
using MblurNeighborMaxTest = VulkanTest;

std::vector<glm::vec4> randomTiles(passes::TileGrid grid, std::mt19937& rng) {
  std::uniform_real_distribution<float> component(-10.0f, 10.0f);
  std::uniform_int_distribution<int> repeat(0, 3);
  std::vector<glm::vec4> tiles(grid.count());
  for (size_t i = 0; i < tiles.size(); ++i) {
    // Some tiles repeat an earlier one, so equal speeds (ties) occur.
    if (i > 0 && repeat(rng) == 0) {
      tiles[i] = tiles[i / 2];
      continue;
    }
    const glm::vec2 v(component(rng), component(rng));
    tiles[i] = glm::vec4(v, glm::length(v), 0.0f);
  }
  return tiles;
}

TEST_F(MblurNeighborMaxTest, RandomGridsMatchTheReferenceExactly) {
  std::mt19937 rng(3);
  const passes::TileGrid grids[] = {{1, 1}, {2, 3}, {17, 11}, {40, 23}};
  for (const passes::TileGrid grid : grids)
    for (uint32_t n : {1u, 3u, 5u, 7u}) {
      const auto tiles = randomTiles(grid, rng);
      const auto device = runNeighborMax(context(), tiles, grid, n);
      const auto reference = neighborMax(tiles, grid, n);
      ASSERT_EQ(device.size(), reference.size());
      for (size_t t = 0; t < device.size(); ++t)
        ASSERT_EQ(device[t], reference[t]) << "tile " << t << " grid " << grid.x << "x" << grid.y << " n " << n;
    }
}

TEST_F(MblurNeighborMaxTest, DilatesExactlyHalfTheNeighbourhoodClampedAtTheBorder) {
  const passes::TileGrid grid{6, 5};
  std::vector<glm::vec4> tiles(grid.count(), glm::vec4(0.0f));
  tiles[0] = {3.0f, 4.0f, 5.0f, 0.0f};  // top-left corner
  const auto device = runNeighborMax(context(), tiles, grid, 5);
  for (uint32_t y = 0; y < grid.y; ++y)
    for (uint32_t x = 0; x < grid.x; ++x)
      EXPECT_EQ(device[y * grid.x + x], (x <= 2 && y <= 2) ? tiles[0] : glm::vec4(0.0f)) << x << "," << y;
}

TEST_F(MblurNeighborMaxTest, TiesGoToTheFirstTileInRowMajorOrder) {
  const passes::TileGrid grid{3, 3};
  std::vector<glm::vec4> tiles(grid.count(), glm::vec4(0.0f));
  tiles[8] = {0.0f, 5.0f, 5.0f, 0.0f};
  tiles[5] = {5.0f, 0.0f, 5.0f, 0.0f};
  tiles[1] = {-3.0f, 4.0f, 5.0f, 0.0f};
  const auto device = runNeighborMax(context(), tiles, grid, 3);
  EXPECT_EQ(device[4], tiles[1]);  // the centre sees all three
  EXPECT_EQ(device[8], tiles[5]);  // the bottom-right corner sees 5 and 8
}

}  // namespace
}  // namespace hmb::test
