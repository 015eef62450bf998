// tile_max_edge_candidates.comp and edge_mask.comp (paper, eqs. 1-4) against the C++ reference on
// random layers of several sizes and on adversarial ones (degenerate velocities, depths and
// normals), the tile-max the first writes against the gather's own, and the 5x5 Sobel against
// values worked out by hand, with thresholds just either side of them.
#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/hybrid/hybrid_harness.h"
#include "tests/hybrid/hybrid_reference.h"
#include "tests/mblur/mblur_harness.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace hybrid;
using passes::RayMaskParameters;

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

RayMaskParameters parametersWith(float edgeThreshold, float softZExtent = 0.03f, float maxSpeed = 40.0f,
                                 float velocityScale = 1.0f) {
  RayMaskParameters p;
  p.blur.tileSize = 13;  // the moving-tile list's tiles: odd, partial 8x8 blocks and partial border tiles
  p.blur.velocityScale = velocityScale;
  p.blur.maxSpeed = maxSpeed;
  p.blur.softZExtent = softZExtent;
  p.edgeThreshold = edgeThreshold;
  return p;
}

// The device's candidate list holds each pixel where eqs. 1 and 2 hold, once, and its
// dispatch covers it in groups of HMB_MASK_LIST_GROUP.
void expectCandidatesMatch(const RayMaskReadback& device, const std::vector<bool>& reference, const std::string& what) {
  std::vector<uint32_t> expected;
  for (size_t i = 0; i < reference.size(); ++i)
    if (reference[i]) expected.push_back(uint32_t(i));
  std::vector<uint32_t> listed = device.candidates;
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, expected) << what << ": edge candidates";
  const uint32_t groups = (device.counters.candidateCount + HMB_MASK_LIST_GROUP - 1) / HMB_MASK_LIST_GROUP;
  const gpu::IndirectDispatch& dispatch = device.counters.dispatches[HMB_RAY_MASK_DISPATCH_CANDIDATES];
  EXPECT_EQ(dispatch.x, std::min(groups, 65535u)) << what << ": candidate dispatch";
  EXPECT_EQ(dispatch.y, (groups + 65534) / 65535) << what << ": candidate dispatch";
}

// The mask's tile-max, which also lists the candidates, is the gather's
// tile_max bit for bit (the gathers blur over the tiles it wrote), and lists each tile whose
// speed is kMinBlurPixels or more once, list_range_blocks' dispatch a lane per block of them.
void expectGatherTileMax(const MaskLayer& layer, const RayMaskParameters& p, const RayMaskReadback& device,
                         const std::string& what) {
  const std::vector<glm::vec4> gather = mblur::runTileMax(VulkanTest::context(), layer.velocity, layer.width,
                                                          layer.height, p.blur.tileSize, p.blur.velocityScale);
  ASSERT_EQ(device.tileMax.size(), gather.size()) << what;
  std::vector<uint32_t> moving;
  for (size_t t = 0; t < gather.size(); ++t) {
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(std::bit_cast<uint32_t>(device.tileMax[t][c]), std::bit_cast<uint32_t>(gather[t][c]))
          << what << ": tile " << t << " component " << c;
    if (gather[t].z >= gpu::kMinBlurPixels) moving.push_back(uint32_t(t));
  }
  std::vector<uint32_t> listed = device.movingTiles;
  std::sort(listed.begin(), listed.end());
  EXPECT_EQ(listed, moving) << what << ": moving tiles";
  const uint32_t blocks = device.counters.tileCount * ((p.blur.tileSize + 7) / 8) * ((p.blur.tileSize + 7) / 8);
  const uint32_t groups = (blocks + 63) / 64;
  EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_TILE_BLOCKS].x, std::min(groups, 65535u)) << what;
  EXPECT_EQ(device.counters.dispatches[HMB_RAY_MASK_DISPATCH_TILE_BLOCKS].y, (groups + 65534u) / 65535u) << what;
}

// The device's edge mask equals the reference's, except at pixels whose x_n lies within 1e-5
// of the threshold (float rounding may order the Sobel sums differently): at most 0.2% of the
// pixels. A flat window (x_n exactly 0) must match exactly, even at threshold 0. Returns how
// many edges the reference marks (callers check the cases mark some, so the comparison means
// something).
size_t expectEdgesMatchWith(const MaskLayer& layer, const RayMaskParameters& p, const std::string& what) {
  const RayMaskReadback device = runRayMask(VulkanTest::context(), layer, p);
  const std::vector<uint32_t> reference = edgeMask(layer, p);
  const std::vector<float> xn = normalizedEdges(layer);
  const std::vector<bool> candidates = edgeCandidates(layer, p);
  expectCandidatesMatch(device, candidates, what);
  expectGatherTileMax(layer, p, device, what);
  EXPECT_EQ(device.edges.size(), reference.size());
  if (device.edges.size() != reference.size()) return 0;
  size_t nearThreshold = 0, wrong = 0, edges = 0;
  for (size_t i = 0; i < reference.size(); ++i) {
    EXPECT_LE(device.edges[i], 1u) << what << ": pixel " << i;
    edges += reference[i];
    if (device.edges[i] == reference[i]) continue;
    if (candidates[i] && xn[i] != 0.0f && std::abs(xn[i] - p.edgeThreshold) <= 1e-5f) {
      ++nearThreshold;
      continue;
    }
    if (++wrong <= 5) {
      ADD_FAILURE() << what << ": pixel (" << i % layer.width << ", " << i / layer.width << ") device "
                    << device.edges[i] << ", reference " << reference[i] << " (x_n " << xn[i] << ", depth "
                    << layer.normalDepth[i].w << ", velocity " << layer.velocity[i].x << "," << layer.velocity[i].y
                    << ")";
    }
  }
  EXPECT_EQ(wrong, 0u) << what;
  EXPECT_LE(nearThreshold, reference.size() / 500) << what << ": pixels within 1e-5 of the threshold that differ";
  return edges;
}

// Both places of the tile-max's test (inside its loop, after it in the tiles that move) list
// the reference's candidates.
size_t expectEdgesMatch(const MaskLayer& layer, RayMaskParameters p, const std::string& what) {
  p.candidatesInTileMaxLoop = false;
  const size_t after = expectEdgesMatchWith(layer, p, what + " (test after the tile-max's loop)");
  p.candidatesInTileMaxLoop = true;
  EXPECT_EQ(expectEdgesMatchWith(layer, p, what + " (test in the loop)"), after) << what;
  return after;
}

using HybridEdgeMaskTest = VulkanTest;

TEST_F(HybridEdgeMaskTest, MatchesReferenceOnRandomLayers) {
  std::mt19937 rng(11);
  struct Size {
    uint32_t width, height;
  };
  for (const float threshold : {0.5f, 0.9f, 0.98f}) {
    size_t edges = 0, pixels = 0;
    for (const Size size : {Size{37, 23}, Size{64, 64}, Size{1, 41}, Size{53, 1}, Size{2, 3}, Size{129, 71}}) {
      const MaskLayer layer = randomMaskLayer(size.width, size.height, rng);
      const std::string what =
          std::to_string(size.width) + "x" + std::to_string(size.height) + " e " + std::to_string(threshold);
      edges += expectEdgesMatch(layer, parametersWith(threshold), what);
      pixels += layer.objectId.size();
    }
    // Edges, but not everywhere: the threshold decides.
    EXPECT_GT(edges, 20u) << "e " << threshold;
    EXPECT_LT(edges, pixels / 4) << "e " << threshold;
  }
}

// The candidates' ranges are clamped to maxSpeed, the tile-max's velocities to the tile size:
// the kernel reuses the tile-max's velocity only where neither clamp acts, so ranges clamped
// tighter than a tile (5 px) or far looser (400 px) list what the reference lists.
TEST_F(HybridEdgeMaskTest, MatchesReferenceWhateverTheRangeClampBesideTheTileSize) {
  std::mt19937 rng(31);
  for (const float maxSpeed : {5.0f, 13.0f, 400.0f}) {
    size_t candidates = 0;
    for (int round = 0; round < 3; ++round) {
      MaskLayer layer = randomMaskLayer(61, 47, rng);
      // Speeds on both sides of the tile size (13) and of maxSpeed.
      std::uniform_real_distribution<float> component(-30.0f, 30.0f);
      for (glm::vec2& v : layer.velocity) v = {component(rng), component(rng)};
      const RayMaskParameters p = parametersWith(0.9f, 0.03f, maxSpeed);
      const std::string what = "maxSpeed " + std::to_string(maxSpeed) + " round " + std::to_string(round);
      expectEdgesMatch(layer, p, what);
      const std::vector<bool> listed = edgeCandidates(layer, p);
      candidates += size_t(std::count(listed.begin(), listed.end(), true));
    }
    EXPECT_GT(candidates, 100u) << "maxSpeed " << maxSpeed;
  }
}

// The tile-max's test visits each tile's pixels HMB_TILE_MAX_GROUP_X / _Y apart: tiles under, at
// and over a lane's single visit (8), odd and even, up to more than 64 visits a lane, list what
// the reference lists.
TEST_F(HybridEdgeMaskTest, ListsTheReferencesCandidatesWhateverTheTileSize) {
  std::mt19937 rng(47);
  MaskLayer layer = randomMaskLayer(157, 93, rng);
  std::uniform_real_distribution<float> component(-12.0f, 12.0f);
  for (glm::vec2& v : layer.velocity) v = {component(rng), component(rng)};
  for (const uint32_t tileSize : {1u, 7u, 8u, 41u, 48u, 64u, 65u, 100u}) {
    RayMaskParameters p = parametersWith(0.9f);
    p.blur.tileSize = tileSize;
    const std::vector<bool> listed = edgeCandidates(layer, p);
    EXPECT_GT(std::count(listed.begin(), listed.end(), true), 200) << "tile " << tileSize;
    expectEdgesMatch(layer, p, "tile " + std::to_string(tileSize));
  }
}

TEST_F(HybridEdgeMaskTest, MatchesReferenceOnOnePixelImages) {
  // A lone pixel ends on itself: never a different object, never an edge.
  MaskLayer layer{1, 1, {glm::vec4(0, 0, 1, 2.0f)}, {glm::vec2(5.0f, -3.0f)}, {4u}};
  EXPECT_EQ(expectEdgesMatch(layer, parametersWith(0.0f), "1x1"), 0u);
  EXPECT_EQ(runRayMask(context(), layer, parametersWith(0.0f)).edges.at(0), 0u);
  // 1xN: a column whose pixels move down onto a deeper object below them.
  layer = {1, 9, {}, {}, {}};
  for (uint32_t y = 0; y < 9; ++y) {
    layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, y < 5 ? 1.0f : 4.0f);
    layer.velocity.emplace_back(0.0f, 2.0f);
    layer.objectId.push_back(y < 5 ? 1u : 2u);
  }
  // Rows 3 and 4 end on the deeper object with the step in their window. The smoothing across a
  // 1-pixel image sums to 16 (clamped), so G_y = 16 (-1 - 2 + 0 + 2 + 4) = 48 at row 3 and
  // 16 (-1 - 2 + 0 + 8 + 4) = 144 at row 4: x_n = 48/49 and 144/145.
  EXPECT_EQ(expectEdgesMatch(layer, parametersWith(0.5f), "1x9 column"), 2u);
  EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(layer, 0, 3, 1.0f)), 48.0f / 49.0f);
  EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(layer, 0, 4, 1.0f)), 144.0f / 145.0f);
}

TEST_F(HybridEdgeMaskTest, MatchesReferenceOnAdversarialLayers) {
  std::mt19937 rng(23);
  size_t edges = 0;
  for (int round = 0; round < 6; ++round) {
    const MaskLayer layer = adversarialMaskLayer(45, 31, rng);
    for (const float threshold : {0.0f, 0.9f, 0.999f})
      for (const float velocityScale : {1.0f, 2.0f})  // 2: 3e38 overflows to infinity when scaled
        edges += expectEdgesMatch(layer, parametersWith(threshold, 0.03f, 40.0f, velocityScale),
                                  "round " + std::to_string(round) + " e " + std::to_string(threshold) + " scale " +
                                      std::to_string(velocityScale));
  }
  EXPECT_GT(edges, 100u);
}

TEST_F(HybridEdgeMaskTest, UniformDegenerateLayersMatchReference) {
  // Whole images of one degenerate depth under a moving object: the Sobel sums overflow or
  // vanish together, and the result still follows the reference.
  for (const float depth : {0.0f, 1e-30f, 1e30f, 3e38f, kNaN, kInf}) {
    MaskLayer layer{24, 16, {}, {}, {}};
    for (uint32_t y = 0; y < layer.height; ++y)
      for (uint32_t x = 0; x < layer.width; ++x) {
        const bool object = x >= 6 && x < 12 && y >= 4 && y < 12;
        layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, object ? 1.0f : depth);
        layer.velocity.emplace_back(object ? glm::vec2(4.0f, 1.0f) : glm::vec2(0.0f));
        layer.objectId.push_back(object ? 7u : 1u);
      }
    for (const float threshold : {0.0f, 0.9f, 0.99f})
      expectEdgesMatch(layer, parametersWith(threshold),
                       "background depth " + std::to_string(depth) + " e " + std::to_string(threshold));
  }
}

// A layer of two vertical halves: columns left of `step` are object 1, the rest object 2.
MaskLayer halves(uint32_t width, uint32_t height, uint32_t step, glm::vec4 left, glm::vec4 right, glm::vec2 velocity) {
  MaskLayer layer{width, height, {}, {}, {}};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      layer.normalDepth.push_back(x < step ? left : right);
      layer.velocity.push_back(velocity);
      layer.objectId.push_back(x < step ? 1u : 2u);
    }
  return layer;
}

// Eq. 2 is strict: an end deeper by exactly SOFT_Z_EXTENT is not an edge; one ulp more is.
TEST_F(HybridEdgeMaskTest, DepthStepExactlyAtSoftZExtentIsNotAnEdge) {
  const float soft = 0.25f, near = 2.0f;
  const float exact = near + soft;
  ASSERT_EQ(exact - near, soft);  // exact in float
  const float further = std::nextafter(exact, kInf);
  for (const float far : {exact, further}) {
    const MaskLayer layer = halves(12, 6, 6, glm::vec4(0, 0, 1, near), glm::vec4(0, 0, 1, far), glm::vec2(3.0f, 0.0f));
    const RayMaskParameters p = parametersWith(0.0f, soft);
    const RayMaskReadback device = runRayMask(context(), layer, p);
    const std::vector<uint32_t> reference = edgeMask(layer, p);
    EXPECT_EQ(device.edges, reference) << "far " << far;
    uint32_t edges = 0;
    for (const uint32_t e : device.edges) edges += e;
    // Columns 3..5 end on the far half; the step is within the Sobel window of 4 and 5 (column
    // 3's window, 1..5, is flat: x_n = 0).
    EXPECT_EQ(edges, far == exact ? 0u : 2u * layer.height) << "far " << far;
  }
  // Equal ids across the same step: eq. 1 fails, no edge however deep.
  MaskLayer same = halves(12, 6, 6, glm::vec4(0, 0, 1, 1.0f), glm::vec4(0, 0, 1, 50.0f), glm::vec2(3.0f, 0.0f));
  same.objectId.assign(same.objectId.size(), 3u);
  for (const uint32_t e : runRayMask(context(), same, parametersWith(0.0f)).edges) EXPECT_EQ(e, 0u);
}

// The 5x5 Sobel by hand. Along a row the derivative weights are (-1 -2 0 2 1), and across it
// the smoothing weights (1 4 6 4 1) sum to 16; a vertical step has no y derivative.
//  - depth 1 | depth 2, the step between columns 4 and 5:
//      column 4 (window 2..6): G_x = 16 (-1 - 2 + 0 + 2*2 + 1*2) = 48,  delta_d = 48 / 1
//      column 3 (window 1..5): G_x = 16 (-1 - 2 + 0 + 2 + 1*2) = 16,    delta_d = 16 / 1
//      column 5 (window 3..7): G_x = 48, delta_d = 48 / 2 = 24
//  - normal (0,0,1) | (0,0,-1) at equal depth: the z components differ by 2:
//      column 4: N_x.z = 16 (-1 - 2 + 0 - 2 - 1) = -96, delta_n = 96
//      column 3: N_x.z = 16 (-1 - 2 + 0 + 2 - 1) = -32, delta_n = 32
// and x_n = 1 - 1 / (x + 1) = x / (x + 1).
TEST_F(HybridEdgeMaskTest, SobelOfADepthStepAndANormalFlipByHand) {
  const uint32_t width = 16, height = 7;
  // Depth step: every pixel moves 3 px right, so columns 2..4 end on the deeper half.
  const MaskLayer step = halves(width, height, 5, glm::vec4(0, 0, 1, 1.0f), glm::vec4(0, 0, 1, 2.0f), glm::vec2(3, 0));
  for (uint32_t y = 0; y < height; ++y) {
    EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(step, 4, int(y), 1.0f)), 48.0f / 49.0f);
    EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(step, 3, int(y), 1.0f)), 16.0f / 17.0f);
    EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(step, 5, int(y), 2.0f)), 24.0f / 25.0f);
    EXPECT_EQ(edgeStrength(step, 2, int(y), 1.0f), 0.0f);
  }
  // Normal flip at depth 1; columns 10.. of object 2 are deeper (depth 3) but outside the
  // windows of columns 3 and 4, which move 7 px right onto them.
  MaskLayer flip = halves(width, height, 5, glm::vec4(0, 0, 1, 1.0f), glm::vec4(0, 0, -1, 1.0f), glm::vec2(7, 0));
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 10; x < width; ++x) flip.normalDepth[y * width + x].w = 3.0f;
  for (uint32_t y = 0; y < height; ++y) {
    EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(flip, 4, int(y), 1.0f)), 96.0f / 97.0f);
    EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(flip, 3, int(y), 1.0f)), 32.0f / 33.0f);
  }

  // The kernel's mask around those values: thresholds just under and over each.
  auto columnsMarked = [&](const MaskLayer& layer, float threshold) {
    const RayMaskReadback device = runRayMask(context(), layer, parametersWith(threshold));
    EXPECT_EQ(device.edges, edgeMask(layer, parametersWith(threshold))) << "e " << threshold;
    std::vector<uint32_t> columns;
    for (uint32_t x = 0; x < width; ++x) {
      uint32_t marked = 0;
      for (uint32_t y = 0; y < height; ++y) marked += device.edges[y * width + x];
      EXPECT_TRUE(marked == 0 || marked == height) << "column " << x << " partly marked at e " << threshold;
      if (marked) columns.push_back(x);
    }
    return columns;
  };
  const float d = 1e-4f;
  using Columns = std::vector<uint32_t>;
  EXPECT_EQ(columnsMarked(step, 48.0f / 49.0f + d), Columns{});
  EXPECT_EQ(columnsMarked(step, 48.0f / 49.0f - d), Columns{4});
  EXPECT_EQ(columnsMarked(step, 16.0f / 17.0f + d), Columns{4});
  EXPECT_EQ(columnsMarked(step, 16.0f / 17.0f - d), (Columns{3, 4}));
  EXPECT_EQ(columnsMarked(step, 0.0f), (Columns{3, 4}));  // column 2's window is flat: x_n = 0, not > 0
  EXPECT_EQ(columnsMarked(flip, 96.0f / 97.0f + d), Columns{});
  EXPECT_EQ(columnsMarked(flip, 96.0f / 97.0f - d), Columns{4});
  EXPECT_EQ(columnsMarked(flip, 32.0f / 33.0f + d), Columns{4});
  EXPECT_EQ(columnsMarked(flip, 32.0f / 33.0f - d), (Columns{3, 4}));
}

// Borders clamp: at column 0 the window is columns (0 0 0 1 2).
TEST_F(HybridEdgeMaskTest, SobelClampsAtTheBorderByHand) {
  // depth 1 in columns 0..1, 2 from column 2: G_x at column 0 = 16 (-1 - 2 + 0 + 2*1 + 1*2) = 16.
  const MaskLayer layer = halves(8, 5, 2, glm::vec4(0, 0, 1, 1.0f), glm::vec4(0, 0, 1, 2.0f), glm::vec2(2.5f, 0));
  EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(layer, 0, 0, 1.0f)), 16.0f / 17.0f);
  // Column 1's window (0 0 1 2 3): G_x = 16 (-1 - 2 + 0 + 2*2 + 1*2) = 48.
  EXPECT_FLOAT_EQ(normalizedEdge(edgeStrength(layer, 1, 4, 1.0f)), 48.0f / 49.0f);
  for (const float threshold : {16.0f / 17.0f - 1e-4f, 16.0f / 17.0f + 1e-4f}) {
    const RayMaskReadback device = runRayMask(context(), layer, parametersWith(threshold));
    EXPECT_EQ(device.edges, edgeMask(layer, parametersWith(threshold)));
    EXPECT_EQ(device.edges[0], threshold < 16.0f / 17.0f ? 1u : 0u) << threshold;
    EXPECT_EQ(device.edges[1], 1u) << threshold;
  }
}

TEST(HybridNormalizedEdgeTest, NonFiniteAndNegativeInputs) {
  EXPECT_EQ(normalizedEdge(kNaN), 0.0f);
  EXPECT_EQ(normalizedEdge(kInf), 1.0f);
  EXPECT_EQ(normalizedEdge(-kInf), 0.0f);
  EXPECT_EQ(normalizedEdge(-3.0f), 0.0f);
  EXPECT_EQ(normalizedEdge(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(normalizedEdge(9.0f), 0.9f);
  EXPECT_EQ(normalizedEdge(3e38f), 1.0f);
}

// Depths beyond the Sobel sums' float range: edgeStrength takes depths relative to the window's
// largest, so a background over 1e37 (NaN and +Inf read as 3e38) is still the strongest edge,
// and a depth step is measured the same at 1e20 units as at 1 (summing raw depths, +Inf and
// -Inf met across the step, and a gradient over 1.8e19 squared to +Inf).
TEST_F(HybridEdgeMaskTest, StepToAnInfinitelyFarBackgroundIsAnEdge) {
  for (const float far : {3e38f, kInf, kNaN}) {
    const MaskLayer layer = halves(12, 7, 6, glm::vec4(0, 0, 1, 1.0f), glm::vec4(0, 0, 1, far), glm::vec2(3.0f, 0.0f));
    const RayMaskReadback device = runRayMask(context(), layer, parametersWith(0.9f));
    uint32_t edges = 0;
    for (uint32_t y = 0; y < layer.height; ++y)
      for (const uint32_t x : {4u, 5u}) edges += device.edges[y * layer.width + x];
    EXPECT_EQ(edges, 2u * layer.height) << "background depth " << far << ": columns 4 and 5 should be edges";
  }
}

TEST_F(HybridEdgeMaskTest, RelativeDepthStepIsScaleInvariantAtHugeDepths) {
  // A 1% step: x_n = 0.32 at depth 1 (delta_d = 48 * 0.01), the same at any scale.
  for (const float scale : {1.0f, 1e20f, 1e30f}) {
    const MaskLayer layer =
        halves(12, 7, 6, glm::vec4(0, 0, 1, scale), glm::vec4(0, 0, 1, 1.01f * scale), glm::vec2(3.0f, 0.0f));
    const RayMaskReadback device = runRayMask(context(), layer, parametersWith(0.5f, 0.001f * scale));
    uint32_t edges = 0;
    for (const uint32_t e : device.edges) edges += e;
    EXPECT_EQ(edges, 0u) << "depth scale " << scale;
  }
}

}  // namespace
}  // namespace hmb::test
