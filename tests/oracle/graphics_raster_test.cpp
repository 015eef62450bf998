// The oracle itself against plain C++ edge functions: coverage (top-left rule), watertight
// shared edges, depth test and z/w interpolation, face culling, odd sizes, scale.
#include "tests/oracle/graphics_raster.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/vec2.hpp>
#include <gtest/gtest.h>

#include "tests/support/vulkan_test.h"

namespace hmb::oracle {
namespace {

using glm::dvec2;

// Twice the signed area of (a, b, p) in framebuffer coordinates (y down).
double edge(dvec2 a, dvec2 b, dvec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

// For a triangle ordered so that edge(p0, p1, p2) > 0: a top edge is horizontal with the
// interior below it, a left edge goes up (the interior is to its right).
bool isTopLeft(dvec2 a, dvec2 b) { return b.y < a.y || (b.y == a.y && b.x > a.x); }

// Reference coverage of the pixel centre (x + 0.5, y + 0.5), top-left rule on ties.
bool covers(dvec2 p0, dvec2 p1, dvec2 p2, uint32_t x, uint32_t y) {
  const double area = edge(p0, p1, p2);
  if (area == 0.0) return false;
  if (area < 0.0) std::swap(p1, p2);
  const dvec2 c(x + 0.5, y + 0.5);
  const dvec2 v[3] = {p0, p1, p2};
  for (int i = 0; i < 3; ++i) {
    const dvec2 a = v[i], b = v[(i + 1) % 3];
    const double e = edge(a, b, c);
    if (e < 0.0 || (e == 0.0 && !isTopLeft(a, b))) return false;
  }
  return true;
}

// A triangle given in framebuffer pixels (y down) at NDC depth z and clip w per vertex.
struct PixelTriangle {
  dvec2 p[3];
  double z[3] = {0.5, 0.5, 0.5};
  double w[3] = {1.0, 1.0, 1.0};
};

OracleTriangle toClip(const PixelTriangle& t, uint32_t width, uint32_t height, uint32_t id, bool doubleSided) {
  OracleTriangle out;
  for (int i = 0; i < 3; ++i) {
    const double ndcX = t.p[i].x / width * 2.0 - 1.0, ndcY = t.p[i].y / height * 2.0 - 1.0;
    out.clip[i] = glm::vec4(float(ndcX * t.w[i]), float(ndcY * t.w[i]), float(t.z[i] * t.w[i]), float(t.w[i]));
  }
  out.id = id;
  out.doubleSided = doubleSided;
  return out;
}

PixelTriangle flat(dvec2 a, dvec2 b, dvec2 c, double z = 0.5) { return {{a, b, c}, {z, z, z}}; }

size_t countNonZero(const std::vector<uint32_t>& ids) {
  return size_t(std::count_if(ids.begin(), ids.end(), [](uint32_t id) { return id != 0; }));
}

class GraphicsOracleTest : public test::VulkanTest {};

TEST_F(GraphicsOracleTest, SingleTriangleCoversCentresInside) {
  const uint32_t W = 16, H = 12;
  // Quarter-pixel vertices: exact on the sub-pixel grid, and no centre lies on an edge.
  const PixelTriangle t = flat({1.25, 0.75}, {14.75, 3.25}, {4.5, 11.25});
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x)
      for (int i = 0; i < 3; ++i)
        ASSERT_NE(edge(t.p[i], t.p[(i + 1) % 3], {x + 0.5, y + 0.5}), 0.0) << "test data puts a centre on an edge";

  const OracleTriangle tri[] = {toClip(t, W, H, 41, true)};
  const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, tri);
  ASSERT_EQ(image.ids.size(), size_t(W) * H);
  size_t covered = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const bool inside = covers(t.p[0], t.p[1], t.p[2], x, y);
      covered += inside;
      EXPECT_EQ(image.idAt(x, y), inside ? 42u : 0u) << "pixel " << x << "," << y;
      EXPECT_EQ(image.depthAt(x, y), inside ? 0.5f : 0.0f) << "pixel " << x << "," << y;
    }
  EXPECT_GT(covered, 40u);
}

TEST_F(GraphicsOracleTest, CentresOnEdgesFollowTopLeftRule) {
  // Vertices on pixel centres: the horizontal, vertical and diagonal edges all pass through
  // centres. Vulkan only requires one of two adjacent triangles to win such a centre; the
  // compute rasterizer must match this device, so the device must use the top-left rule.
  const uint32_t W = 13, H = 11;
  const PixelTriangle upperLeft = flat({2.5, 1.5}, {10.5, 1.5}, {2.5, 9.5});   // top + left edges
  const PixelTriangle lowerRight = flat({10.5, 1.5}, {10.5, 9.5}, {2.5, 9.5});  // right + bottom edges
  for (const PixelTriangle& t : {upperLeft, lowerRight}) {
    const OracleTriangle tri[] = {toClip(t, W, H, 0, true)};
    const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, tri);
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x)
        EXPECT_EQ(image.idAt(x, y), covers(t.p[0], t.p[1], t.p[2], x, y) ? 1u : 0u) << "pixel " << x << "," << y;
  }
}

TEST_F(GraphicsOracleTest, SharedDiagonalIsWatertight) {
  // A quad split along a diagonal through the centres (0.5 + 2k, 0.5 + k); the outer edges
  // miss every centre, so exactly the 13x7 centres inside must be covered, each once.
  const uint32_t W = 16, H = 8;
  const dvec2 a{0.0, 0.25}, b{13.0, 0.25}, c{13.0, 6.75}, d{0.0, 6.75};
  const PixelTriangle upper = flat(a, c, b), lower = flat(a, d, c);  // both front-facing
  const OracleTriangle first[] = {toClip(upper, W, H, 0, false)};
  const OracleTriangle second[] = {toClip(lower, W, H, 1, false)};
  const OracleTriangle both[] = {first[0], second[0]};
  const OracleImage imageUpper = rasterizeWithGraphicsPipeline(context(), W, H, first);
  const OracleImage imageLower = rasterizeWithGraphicsPipeline(context(), W, H, second);
  const OracleImage imageBoth = rasterizeWithGraphicsPipeline(context(), W, H, both);

  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const bool inQuad = x <= 12 && y <= 6;
      const int hits = (imageUpper.idAt(x, y) != 0) + (imageLower.idAt(x, y) != 0);
      EXPECT_EQ(hits, inQuad ? 1 : 0) << "pixel " << x << "," << y;
      EXPECT_EQ(imageUpper.idAt(x, y) != 0, covers(a, c, b, x, y)) << "pixel " << x << "," << y;
      const uint32_t expected = imageUpper.idAt(x, y) ? 1u : (imageLower.idAt(x, y) ? 2u : 0u);
      EXPECT_EQ(imageBoth.idAt(x, y), expected) << "pixel " << x << "," << y;
    }
  EXPECT_EQ(countNonZero(imageBoth.ids), 13u * 7u);
}

TEST_F(GraphicsOracleTest, NearerTriangleWinsInEitherOrder) {
  const uint32_t W = 20, H = 16;
  const PixelTriangle far = flat({1.25, 1.25}, {18.75, 2.25}, {3.25, 14.75}, 0.25);  // reversed depth
  const PixelTriangle near = flat({6.25, 4.75}, {19.25, 8.25}, {8.75, 15.25}, 0.75);
  const OracleTriangle farTri = toClip(far, W, H, 10, true), nearTri = toClip(near, W, H, 20, true);
  for (const auto& order : {std::vector{farTri, nearTri}, std::vector{nearTri, farTri}}) {
    const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, order);
    size_t overlap = 0;
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const bool inNear = covers(near.p[0], near.p[1], near.p[2], x, y);
        const bool inFar = covers(far.p[0], far.p[1], far.p[2], x, y);
        overlap += inNear && inFar;
        EXPECT_EQ(image.idAt(x, y), inNear ? 21u : (inFar ? 11u : 0u)) << "pixel " << x << "," << y;
        EXPECT_EQ(image.depthAt(x, y), inNear ? 0.75f : (inFar ? 0.25f : 0.0f)) << "pixel " << x << "," << y;
      }
    EXPECT_GT(overlap, 10u);
  }
}

TEST_F(GraphicsOracleTest, DepthIsZOverWInterpolatedInScreenSpace) {
  const uint32_t W = 24, H = 20;
  PixelTriangle t = flat({1.25, 2.75}, {9.25, 18.75}, {22.75, 1.25});
  // Different w per vertex: the depth is z/w interpolated linearly on screen, not perspective-correct.
  t.z[0] = 0.1, t.z[1] = 0.5, t.z[2] = 0.9;
  t.w[0] = 1.0, t.w[1] = 2.0, t.w[2] = 4.0;
  const OracleTriangle tri[] = {toClip(t, W, H, 7, false)};
  ASSERT_LT(edge(t.p[0], t.p[1], t.p[2]), 0.0) << "front-facing by construction";
  const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, tri);

  const double area = edge(t.p[0], t.p[1], t.p[2]);
  size_t checked = 0;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const bool inside = covers(t.p[0], t.p[1], t.p[2], x, y);
      ASSERT_EQ(image.idAt(x, y), inside ? 8u : 0u) << "pixel " << x << "," << y;
      if (!inside) {
        EXPECT_EQ(image.depthAt(x, y), 0.0f);
        continue;
      }
      const dvec2 c(x + 0.5, y + 0.5);
      const double l0 = edge(t.p[1], t.p[2], c) / area, l1 = edge(t.p[2], t.p[0], c) / area;
      const double expected = l0 * t.z[0] + l1 * t.z[1] + (1.0 - l0 - l1) * t.z[2];
      EXPECT_NEAR(image.depthAt(x, y), expected, 1e-5) << "pixel " << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, 100u);
}

TEST_F(GraphicsOracleTest, BackFacesAreCulledUnlessDoubleSided) {
  const uint32_t W = 12, H = 12;
  // Counter-clockwise as the image is seen (row 0 on top): down the left side, then up-right.
  const PixelTriangle front = flat({2.25, 2.25}, {2.25, 9.75}, {9.75, 2.25});
  const PixelTriangle back = flat(front.p[0], front.p[2], front.p[1]);
  ASSERT_LT(edge(front.p[0], front.p[1], front.p[2]), 0.0);

  const OracleTriangle frontSingle[] = {toClip(front, W, H, 0, false)};
  const OracleTriangle backSingle[] = {toClip(back, W, H, 0, false)};
  const OracleTriangle backDouble[] = {toClip(back, W, H, 0, true)};
  const OracleImage drawn = rasterizeWithGraphicsPipeline(context(), W, H, frontSingle);
  const OracleImage culled = rasterizeWithGraphicsPipeline(context(), W, H, backSingle);
  const OracleImage twoSided = rasterizeWithGraphicsPipeline(context(), W, H, backDouble);
  EXPECT_GT(countNonZero(drawn.ids), 20u);
  EXPECT_EQ(countNonZero(culled.ids), 0u);
  EXPECT_EQ(twoSided.ids, drawn.ids);
  EXPECT_EQ(twoSided.depth, drawn.depth);
}

TEST_F(GraphicsOracleTest, GltfCounterClockwiseIsFrontAfterYFlip) {
  // A glTF triangle counter-clockwise in a y-up view, through a projection that negates y
  // for Vulkan's y-down NDC, must survive back-face culling.
  const glm::vec2 view[3] = {{-0.5f, -0.5f}, {0.5f, -0.5f}, {0.0f, 0.5f}};  // CCW with y up
  OracleTriangle t;
  for (int i = 0; i < 3; ++i) t.clip[i] = glm::vec4(view[i].x, -view[i].y, 0.5f, 1.0f);
  t.id = 3;
  const OracleTriangle front[] = {t};
  std::swap(t.clip[1], t.clip[2]);
  const OracleTriangle back[] = {t};
  EXPECT_GT(countNonZero(rasterizeWithGraphicsPipeline(context(), 8, 8, front).ids), 0u);
  EXPECT_EQ(countNonZero(rasterizeWithGraphicsPipeline(context(), 8, 8, back).ids), 0u);
}

TEST_F(GraphicsOracleTest, EqualDepthTiesGoToTheEarlierTriangleInTheSpan) {
  // Single- and double-sided triangles go to separate draws; the draws keep the span's order,
  // so the LESS test keeps the first of several coplanar triangles.
  const uint32_t W = 8, H = 8;
  const PixelTriangle t = flat({0.25, 0.25}, {0.25, 7.75}, {7.75, 0.25});
  const OracleTriangle a = toClip(t, W, H, 10, false), b = toClip(t, W, H, 20, true), c = toClip(t, W, H, 30, false);
  const OracleImage abc = rasterizeWithGraphicsPipeline(context(), W, H, std::vector{a, b, c});
  const OracleImage bac = rasterizeWithGraphicsPipeline(context(), W, H, std::vector{b, a, c});
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const bool inside = covers(t.p[0], t.p[1], t.p[2], x, y);
      EXPECT_EQ(abc.idAt(x, y), inside ? 11u : 0u) << "pixel " << x << "," << y;
      EXPECT_EQ(bac.idAt(x, y), inside ? 21u : 0u) << "pixel " << x << "," << y;
    }
}

TEST_F(GraphicsOracleTest, DepthOutsideZeroToOneIsClipped) {
  // Depth clamp is off: z/w runs from -0.5 at the left edge to 1.5 at the right, and only
  // the middle half of the image (0 <= z/w <= 1) is drawn.
  const uint32_t W = 16, H = 4;
  OracleTriangle full;
  full.clip[0] = {-1.0f, -1.0f, -0.5f, 1.0f};
  full.clip[1] = {-1.0f, 3.0f, -0.5f, 1.0f};
  full.clip[2] = {3.0f, -1.0f, 3.5f, 1.0f};
  const OracleTriangle tri[] = {full};
  const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, tri);
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const double z = -0.5 + 2.0 * (x + 0.5) / W;
      EXPECT_EQ(image.idAt(x, y), z >= 0.0 && z <= 1.0 ? 1u : 0u) << "pixel " << x << "," << y;
    }
}

TEST_F(GraphicsOracleTest, OddSizesAndZeroTriangles) {
  for (const auto& [W, H] : {std::pair{1u, 1u}, std::pair{7u, 3u}}) {
    const OracleImage empty = rasterizeWithGraphicsPipeline(context(), W, H, {});
    EXPECT_EQ(empty.width, W);
    EXPECT_EQ(empty.height, H);
    EXPECT_EQ(empty.ids, std::vector<uint32_t>(size_t(W) * H, 0u));
    EXPECT_EQ(empty.depth, std::vector<float>(size_t(W) * H, 0.0f));

    // One triangle that contains the whole viewport.
    OracleTriangle full;
    full.clip[0] = {-1.0f, -1.0f, 0.25f, 1.0f};
    full.clip[1] = {-1.0f, 3.0f, 0.25f, 1.0f};
    full.clip[2] = {3.0f, -1.0f, 0.25f, 1.0f};
    full.id = 99;
    const OracleTriangle tri[] = {full};
    const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, tri);
    EXPECT_EQ(image.ids, std::vector<uint32_t>(size_t(W) * H, 100u));
    EXPECT_EQ(image.depth, std::vector<float>(size_t(W) * H, 0.25f));
  }
}

TEST_F(GraphicsOracleTest, RasterizerIsReusableAndTimesTheDraw) {
  const uint32_t W = 9, H = 5;
  GraphicsRasterizer rasterizer(context(), W, H);
  const OracleTriangle big[] = {toClip(flat({0.25, 0.25}, {0.25, 4.75}, {8.75, 0.25}), W, H, 1, false),
                                toClip(flat({8.75, 4.75}, {8.75, 0.25}, {0.25, 4.75}), W, H, 2, false)};
  const OracleTriangle small[] = {toClip(flat({2.25, 1.25}, {2.25, 3.75}, {6.75, 1.25}), W, H, 3, true)};
  for (int round = 0; round < 2; ++round) {
    EXPECT_EQ(rasterizer.rasterize(big).ids, rasterizeWithGraphicsPipeline(context(), W, H, big).ids);
    EXPECT_EQ(rasterizer.rasterize(small).ids, rasterizeWithGraphicsPipeline(context(), W, H, small).ids);
    EXPECT_EQ(countNonZero(rasterizer.rasterize({}).ids), 0u);
  }
  EXPECT_EQ(rasterizer.lastDrawMilliseconds().has_value(), context().info().timestamps);
  if (rasterizer.lastDrawMilliseconds()) {
    EXPECT_GE(*rasterizer.lastDrawMilliseconds(), 0.0);
  }
}

TEST_F(GraphicsOracleTest, MillionTrianglesNearestLayerWins) {
  // 8 layers of two triangles per pixel cell (2^20 triangles); layer 5 is nearest, drawn
  // neither first nor last. Each cell's diagonal passes through its centre, so the top-left
  // rule decides which of the cell's two triangles is seen.
  const uint32_t W = 256, H = 256, layers = 8, nearest = 5;
  std::vector<OracleTriangle> triangles;
  triangles.reserve(size_t(W) * H * 2 * layers);
  std::vector<PixelTriangle> cell;  // the two triangles of each cell, in id order
  for (uint32_t layer = 0; layer < layers; ++layer) {
    const double z = layer == nearest ? 0.875 : 0.75 - 0.0625 * layer;  // reversed: nearest largest
    for (uint32_t y = 0; y < H; ++y)
      for (uint32_t x = 0; x < W; ++x) {
        const dvec2 p00(x, y), p10(x + 1, y), p11(x + 1, y + 1), p01(x, y + 1);
        const PixelTriangle halves[2] = {flat(p00, p11, p10, z), flat(p00, p01, p11, z)};
        for (const PixelTriangle& half : halves) {
          triangles.push_back(toClip(half, W, H, uint32_t(triangles.size()), false));
          if (layer == 0) cell.push_back(half);
        }
      }
  }
  ASSERT_EQ(triangles.size(), size_t(1) << 20);
  const OracleImage image = rasterizeWithGraphicsPipeline(context(), W, H, triangles);
  const uint32_t layerBase = nearest * W * H * 2;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const uint32_t first = 2 * (y * W + x);
      const PixelTriangle& upper = cell[first];
      const uint32_t half = covers(upper.p[0], upper.p[1], upper.p[2], x, y) ? 0 : 1;
      ASSERT_EQ(image.idAt(x, y), layerBase + first + half + 1) << "pixel " << x << "," << y;
      ASSERT_EQ(image.depthAt(x, y), 0.875f) << "pixel " << x << "," << y;
    }
}

}  // namespace
}  // namespace hmb::oracle
