// The rasterizer's kernels (setup_triangles, bin_large_triangles, rasterize_tiles and its
// 32-bit two-pass fallback) against the plain C++ reference of the same math
// (raster_reference.h): seeded random triangles at odd image sizes, and adversarial inputs
// (pixel-centre ties, degenerate and non-finite vertices, w <= 0, huge coordinates, a
// screen-covering triangle, equal-depth overlaps). Every visibility check runs with both
// schemes, and the two schemes must give the very same visibility buffer.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/raster/raster_harness.h"
#include "tests/raster/raster_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using passes::VisibilityScheme;
constexpr VisibilityScheme kSchemes[] = {VisibilityScheme::Int64Atomics, VisibilityScheme::Depth32TwoPass,
                                         VisibilityScheme::TileLists};
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Clip-space position of a screen point (pixels, y down) at depth z/w, scaled by w.
glm::vec4 atScreen(float sx, float sy, float depth, uint32_t width, uint32_t height, float w = 1.0f) {
  const float ndcX = sx / float(width) * 2.0f - 1.0f;
  const float ndcY = sy / float(height) * 2.0f - 1.0f;
  return {ndcX * w, ndcY * w, depth * w, w};
}

float depthOf(uint32_t key) { return gpu::depthOfKey(key); }

std::string describe(const gpu::SetupTriangle& s) {
  std::ostringstream os;
  os << "triangle " << s.triangle << " p0 (" << s.p0.x << ", " << s.p0.y << ") p1 (" << s.p1.x << ", " << s.p1.y
     << ") p2 (" << s.p2.x << ", " << s.p2.y << ") depth (" << s.depth.x << ", " << s.depth.y << ", " << s.depth.z
     << ") bounds (" << s.pixelBounds.x << ", " << s.pixelBounds.y << ")-(" << s.pixelBounds.z << ", "
     << s.pixelBounds.w << ")";
  return os.str();
}

bool depthClose(float kernel, float reference) {
  return std::abs(kernel - reference) <= 1e-6f * std::max(1.0f, std::abs(reference));
}

bool withinAStep(glm::vec2 kernel, glm::vec2 reference) {
  const glm::vec2 apart = glm::abs(kernel - reference) * float(HMB_RASTER_SUBPIXEL);
  return apart.x <= 1.0f && apart.y <= 1.0f;
}

bool withinAPixel(glm::uvec4 kernel, glm::uvec4 reference) {
  for (int c = 0; c < 4; ++c)
    if (std::max(kernel[c], reference[c]) - std::min(kernel[c], reference[c]) > 1u) return false;
  return true;
}

// The setup kernel's output and the reference's as sets (the kernel's order follows its atomics).
void expectSetupMatches(std::vector<gpu::SetupTriangle> kernel, std::vector<gpu::SetupTriangle> reference) {
  std::sort(kernel.begin(), kernel.end(), reference::setupLess);
  std::sort(reference.begin(), reference.end(), reference::setupLess);
  if (kernel.size() != reference.size()) {
    // Name the scene triangles whose count of set-up triangles differs.
    std::map<uint32_t, int> difference;
    for (const auto& s : kernel) ++difference[s.triangle];
    for (const auto& s : reference) --difference[s.triangle];
    std::ostringstream os;
    for (const auto& [triangle, d] : difference)
      if (d != 0) os << " triangle " << triangle << ": kernel " << (d > 0 ? "+" : "") << d << ";";
    ADD_FAILURE() << "setup: kernel wrote " << kernel.size() << " triangles, reference " << reference.size() << ":"
                  << os.str();
    return;
  }
  int failures = 0;
  for (size_t i = 0; i < kernel.size() && failures < 8; ++i) {
    const gpu::SetupTriangle &k = kernel[i], &r = reference[i];
    // A vertex snaps x / w to a sub-pixel step. Vulkan lets the division be off by 2.5 ULP
    // ("Precision and Operation of SPIR-V Instructions"), under a step anywhere in the guard band,
    // so a quotient next to the middle between two steps may snap to the other one, and move a
    // pixel bound by one; where every vertex snaps as the reference's, the bounds are equal.
    const bool sameSnaps = k.p0 == r.p0 && k.p1 == r.p1 && k.p2 == r.p2;
    const bool snapsWithinAStep = withinAStep(k.p0, r.p0) && withinAStep(k.p1, r.p1) && withinAStep(k.p2, r.p2);
    const bool boundsOk = sameSnaps ? k.pixelBounds == r.pixelBounds : withinAPixel(k.pixelBounds, r.pixelBounds);
    const bool same = k.triangle == r.triangle && snapsWithinAStep && boundsOk && depthClose(k.depth.x, r.depth.x) &&
                      depthClose(k.depth.y, r.depth.y) && depthClose(k.depth.z, r.depth.z);
    if (!same) {
      ++failures;
      ADD_FAILURE() << "setup differs:\n  kernel    " << describe(k) << "\n  reference " << describe(r);
    }
  }
}

// Every set-up triangle owns the pairs [firstPair, firstPair + tiles) naming it and its tiles
// row by row, whether setup_triangles or bin_large_triangles wrote them.
void expectBinningMatches(const Visibility& v) {
  const uint32_t tilesX = reference::tilesAcross(v.width);
  size_t total = 0, large = 0, wrong = 0;
  for (uint32_t slot = 0; slot < v.setup.size(); ++slot) {
    const gpu::SetupTriangle& s = v.setup[slot];
    const std::vector<uint32_t> tiles = reference::triangleTiles(s, tilesX);
    total += tiles.size();
    large += tiles.size() > HMB_RASTER_LARGE_TILES;
    ASSERT_LE(uint64_t(s.firstPair) + tiles.size(), v.pairs.size()) << describe(s);
    for (size_t k = 0; k < tiles.size(); ++k) {
      const glm::uvec2 pair = v.pairs[s.firstPair + k];
      if (pair != glm::uvec2(slot, tiles[k]) && ++wrong <= 8)
        ADD_FAILURE() << "pair " << s.firstPair + k << " is (" << pair.x << ", " << pair.y << "), expected (" << slot
                      << ", " << tiles[k] << ") for " << describe(s);
    }
  }
  // Ranges that each name their own slot and add up to the pair count cannot overlap.
  EXPECT_EQ(total, v.pairs.size());
  EXPECT_EQ(large, v.stats.largeTriangles);
  EXPECT_EQ(wrong, 0u);
}

struct PixelAgreement {
  size_t pixels = 0, sameIds = 0, depthMismatches = 0;
  double fraction() const { return pixels == 0 ? 1.0 : double(sameIds) / double(pixels); }
};

PixelAgreement compareVisibility(const Visibility& kernel, const reference::ReferenceVisibility& expected,
                                 std::string* firstMismatches) {
  PixelAgreement a;
  a.pixels = size_t(kernel.width) * kernel.height;
  std::ostringstream os;
  int listed = 0;
  for (uint32_t y = 0; y < kernel.height; ++y) {
    for (uint32_t x = 0; x < kernel.width; ++x) {
      const size_t i = size_t(y) * kernel.width + x;
      const glm::uvec2 k = kernel.entries[i], r = expected.entries[i];
      const bool sameId = k.x == r.x;
      a.sameIds += sameId;
      // Empty pixels must be fully cleared (depth keys too); covered ones within 1e-6 in depth.
      const bool depthOk = r.x == HMB_VIS_EMPTY ? k.y == r.y : std::abs(depthOf(k.y) - depthOf(r.y)) <= 1e-6f;
      if (sameId && !depthOk) ++a.depthMismatches;
      if ((!sameId || !depthOk) && listed++ < 6)
        os << "\n  pixel (" << x << ", " << y << "): kernel id " << k.x << " depth " << depthOf(k.y)
           << ", reference id " << r.x << " depth " << depthOf(r.y) << " (covered by " << expected.coverage[i]
           << ")";
    }
  }
  *firstMismatches = os.str();
  return a;
}

// Runs the input through both schemes and checks setup, binning and visibility against the
// reference; returns the smaller id agreement of the two schemes.
double expectMatchesReference(const ClipTriangles& input, uint32_t width, uint32_t height, double minIdAgreement) {
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, width, height);
  const reference::ReferenceVisibility expected = reference::rasterizeReference(setup, width, height);
  double worst = 1.0;
  std::optional<Visibility> first;
  for (VisibilityScheme scheme : kSchemes) {
    SCOPED_TRACE(std::string(passes::visibilitySchemeName(scheme)) + " at " + std::to_string(width) + "x" +
                 std::to_string(height));
    const Visibility v = rasterizeClipTriangles(VulkanTest::context(), input, width, height, scheme);
    EXPECT_EQ(v.stats.setupTriangles, setup.size());
    expectSetupMatches(v.setup, setup);
    expectBinningMatches(v);
    std::string mismatches;
    const PixelAgreement a = compareVisibility(v, expected, &mismatches);
    EXPECT_GE(a.fraction(), minIdAgreement)
        << a.pixels - a.sameIds << " of " << a.pixels << " pixels differ:" << mismatches;
    EXPECT_EQ(a.depthMismatches, 0u) << mismatches;
    worst = std::min(worst, a.fraction());
    if (first) {
      size_t differ = 0;
      for (size_t i = 0; i < v.entries.size(); ++i) differ += v.entries[i] != first->entries[i];
      EXPECT_EQ(differ, 0u) << "the two visibility schemes disagree";
    } else {
      first = v;
    }
  }
  return worst;
}

// ---- seeded random triangles ----

ClipTriangles randomTriangles(uint32_t seed, int count) {
  std::mt19937 rng(seed);
  auto uniform = [&](float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); };
  auto logUniform = [&](float lo, float hi) { return std::exp(uniform(std::log(lo), std::log(hi))); };
  ClipTriangles input;
  for (int t = 0; t < count; ++t) {
    // NDC sizes from a hundredth of a pixel to many screens (past the 4x guard band).
    const glm::vec2 centre(uniform(-1.4f, 1.4f), uniform(-1.4f, 1.4f));
    const float size = logUniform(2e-4f, 12.0f);
    const int beforeNear = rng() % 6 == 0 ? 1 + int(rng() % 2) : 0;  // vertices with z > w
    glm::vec4 v[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec2 ndc = centre + size * glm::vec2(uniform(-1, 1), uniform(-1, 1));
      float depth = uniform(0.01f, 0.99f);
      if (k < beforeNear) depth = uniform(1.01f, 3.0f);     // reversed depth: nearer than the near plane
      if (rng() % 25 == 0) depth = uniform(-0.5f, 0.0f);  // beyond the far plane
      const float w = logUniform(0.1f, 10.0f);
      v[k] = glm::vec4(ndc.x * w, ndc.y * w, depth * w, w);
    }
    input.add(v[0], v[1], v[2], rng() % 2 == 0);
  }
  return input;
}

class RasterizeKernelTest : public VulkanTest {};

TEST_F(RasterizeKernelTest, RandomTrianglesMatchReference) {
  struct Case {
    uint32_t width, height, seed;
    int triangles;
  };
  for (const Case& c : {Case{67, 43, 1u, 400}, Case{1, 1, 2u, 300}, Case{257, 129, 3u, 300}}) {
    SCOPED_TRACE("seed " + std::to_string(c.seed));
    const ClipTriangles input = randomTriangles(c.seed, c.triangles);
    const double agreement = expectMatchesReference(input, c.width, c.height, 0.999);
    RecordProperty("id_agreement_" + std::to_string(c.width) + "x" + std::to_string(c.height),
                   std::to_string(agreement));
  }
}

// The random inputs must exercise what they claim to: clipping, large binning, both facings.
TEST_F(RasterizeKernelTest, RandomTrianglesExerciseEveryPath) {
  const ClipTriangles input = randomTriangles(3u, 300);
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, 257, 129);
  std::map<uint32_t, int> perTriangle;
  size_t large = 0;
  for (const auto& s : setup) {
    ++perTriangle[s.triangle];
    large += reference::triangleTiles(s, reference::tilesAcross(257)).size() > HMB_RASTER_LARGE_TILES;
  }
  size_t split = 0, nearClipped = 0, guardClipped = 0;
  for (const auto& [triangle, n] : perTriangle) {
    split += n > 1;
    const gpu::GpuTriangle& tri = input.triangles[triangle];
    bool behindNear = false, pastGuardBand = false;
    for (uint32_t v : {tri.v0, tri.v1, tri.v2}) {
      const glm::vec4 c = input.clip[v];
      behindNear = behindNear || c.z < 0.0f;
      pastGuardBand = pastGuardBand || std::abs(c.x) > 4.0f * c.w || std::abs(c.y) > 4.0f * c.w;
    }
    nearClipped += behindNear;
    guardClipped += pastGuardBand;
  }
  EXPECT_GE(split, 10u) << "clipping should split some triangles";
  EXPECT_GE(nearClipped, 10u) << "some visible triangles should cross the near plane";
  EXPECT_GE(guardClipped, 10u) << "some visible triangles should cross the guard band";
  EXPECT_GE(large, 5u) << "some triangles should take the large-triangle binning path";
  EXPECT_LT(perTriangle.size(), input.triangles.size()) << "culling should drop some triangles";
  const reference::ReferenceVisibility visible = reference::rasterizeReference(setup, 257, 129);
  size_t covered = 0;
  for (const glm::uvec2& e : visible.entries) covered += e.x != HMB_VIS_EMPTY;
  EXPECT_GT(covered, size_t(257) * 129 / 2);
}

// ---- adversarial inputs (exactly representable coordinates: 100% agreement) ----

// A lattice of triangles whose vertices sit on pixel centres, with both diagonals, so edges
// run horizontally, vertically and diagonally through centres and are shared.
TEST_F(RasterizeKernelTest, PixelCentreVerticesAndSharedEdgesMatchReference) {
  for (auto [width, height] : {std::pair<uint32_t, uint32_t>{16, 16}, {13, 11}}) {
    ClipTriangles input;
    for (uint32_t j = 0; j + 3 < height; j += 3) {
      for (uint32_t i = 0; i + 3 < width; i += 3) {
        const float x0 = float(i) + 0.5f, y0 = float(j) + 0.5f, x1 = x0 + 3.0f, y1 = y0 + 3.0f;
        const glm::vec4 a = atScreen(x0, y0, 0.5f, width, height), b = atScreen(x1, y0, 0.5f, width, height),
                        c = atScreen(x1, y1, 0.5f, width, height), d = atScreen(x0, y1, 0.5f, width, height);
        if ((i + j) % 2 == 0) {
          input.add(a, b, c);
          input.add(a, c, d);
        } else {
          input.add(a, b, d);
          input.add(b, c, d);
        }
      }
    }
    // Fan around a pixel centre: edges through centres at 45 and 90 degrees.
    const float cx = 6.5f, cy = 5.5f;
    const glm::vec2 ring[] = {{-2, -2}, {0, -2}, {2, -2}, {2, 0}, {2, 2}, {0, 2}, {-2, 2}, {-2, 0}};
    for (int k = 0; k < 8; ++k) {
      const glm::vec2 p = ring[k], q = ring[(k + 1) % 8];
      input.add(atScreen(cx, cy, 0.25f, width, height), atScreen(cx + p.x, cy + p.y, 0.25f, width, height),
                atScreen(cx + q.x, cy + q.y, 0.25f, width, height));
    }
    const std::vector<gpu::SetupTriangle> setup =
        reference::setupTriangles(input.clip, input.triangles, input.doubleSided, width, height);
    const reference::ReferenceVisibility expected = reference::rasterizeReference(setup, width, height);
    // Shared edges: no centre is covered twice within the lattice or within the fan.
    const uint32_t maxCoverage = *std::max_element(expected.coverage.begin(), expected.coverage.end());
    EXPECT_LE(maxCoverage, 2u) << "at most one lattice and one fan triangle per centre";
    expectMatchesReference(input, width, height, 1.0);
  }
}

// Independent of the reference: a square with corners on pixel centres (2.5, 2.5)-(6.5, 6.5)
// covers x, y in [2, 5] exactly once, whichever diagonal splits it (top-left rule: top and
// left edges own their centres, bottom and right edges do not).
TEST_F(RasterizeKernelTest, TopLeftRuleOwnsTopAndLeftEdges) {
  constexpr uint32_t kSize = 9;
  for (bool otherDiagonal : {false, true}) {
    ClipTriangles input;
    const glm::vec4 a = atScreen(2.5f, 2.5f, 0.5f, kSize, kSize), b = atScreen(6.5f, 2.5f, 0.5f, kSize, kSize),
                    c = atScreen(6.5f, 6.5f, 0.5f, kSize, kSize), d = atScreen(2.5f, 6.5f, 0.5f, kSize, kSize);
    if (otherDiagonal) {
      input.add(a, b, d);
      input.add(b, c, d);
    } else {
      input.add(a, b, c);
      input.add(a, c, d);
    }
    for (VisibilityScheme scheme : kSchemes) {
      SCOPED_TRACE(passes::visibilitySchemeName(scheme));
      const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
      for (uint32_t y = 0; y < kSize; ++y)
        for (uint32_t x = 0; x < kSize; ++x) {
          const bool inside = x >= 2 && x <= 5 && y >= 2 && y <= 5;
          EXPECT_EQ(v.idAt(x, y) != HMB_VIS_EMPTY, inside) << "pixel (" << x << ", " << y << ")";
        }
    }
    expectMatchesReference(input, kSize, kSize, 1.0);
  }
}

// Facing: front faces have negative area in y-down pixels; single-sided back faces are culled.
TEST_F(RasterizeKernelTest, BackFacesOfSingleSidedTrianglesAreCulled) {
  constexpr uint32_t kSize = 8;
  const glm::vec4 a = atScreen(1, 1, 0.5f, kSize, kSize), b = atScreen(7, 1, 0.5f, kSize, kSize),
                  c = atScreen(1, 7, 0.5f, kSize, kSize);
  ClipTriangles input;
  input.add(a, b, c, false);  // area > 0: back face, culled
  input.add(a, c, b, false);  // area < 0: front face, kept (swapped to positive area)
  input.add(a, b, c, true);   // back face of a double-sided triangle, kept
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kSize, kSize);
  ASSERT_EQ(setup.size(), 2u);
  EXPECT_EQ(setup[0].triangle, 1u);
  EXPECT_EQ(setup[1].triangle, 2u);
  expectMatchesReference(input, kSize, kSize, 1.0);
}

TEST_F(RasterizeKernelTest, ZeroAreaAndCollinearTrianglesAreDropped) {
  constexpr uint32_t kSize = 16;
  auto at = [&](float x, float y) { return atScreen(x, y, 0.5f, kSize, kSize); };
  ClipTriangles input;
  input.add(at(2.5f, 2.5f), at(2.5f, 2.5f), at(9.5f, 4.5f));     // repeated vertex
  input.add(at(1.5f, 1.5f), at(5.5f, 5.5f), at(9.5f, 9.5f));     // collinear through centres
  input.add(at(1.5f, 3.5f), at(14.5f, 3.5f), at(7.5f, 3.5f));    // collinear along a row of centres
  input.add(at(3.5f, 1.0f), at(3.5f, 15.0f), at(3.5f, 8.0f));    // collinear along a column
  input.add(at(4, 4), at(4, 4), at(4, 4));                       // a point
  input.add(at(2, 2), at(12, 12), at(7.0001f, 7.0f));            // collinear once snapped to 1/256
  input.add(at(1.5f, 10.5f), at(10.5f, 10.5f), at(1.5f, 14.5f));  // the one real triangle
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kSize, kSize);
  ASSERT_EQ(setup.size(), 1u);
  EXPECT_EQ(setup[0].triangle, 6u);
  expectMatchesReference(input, kSize, kSize, 1.0);
}

// NaN/Inf vertices are dropped; w = 0, negative w and huge coordinates neither crash nor
// produce out-of-image writes, and match the reference.
TEST_F(RasterizeKernelTest, NonFiniteZeroAndNegativeWAndHugeCoordinates) {
  constexpr uint32_t kSize = 32;
  const glm::vec4 a(-0.5f, -0.5f, 0.5f, 1.0f), b(0.5f, -0.5f, 0.5f, 1.0f), c(0.0f, 0.5f, 0.5f, 1.0f);
  ClipTriangles input;
  for (float bad : {kNan, kInf, -kInf}) {
    for (int component = 0; component < 4; ++component) {
      glm::vec4 v = c;
      v[component] = bad;
      input.add(a, b, v);
    }
  }
  const uint32_t firstFinite = static_cast<uint32_t>(input.triangles.size());
  input.add(a, b, glm::vec4(0, 0, 0, 0));                                   // w = 0 at the eye
  input.add(a, b, glm::vec4(0.25f, 0.5f, 0.5f, 0.0f));                      // w = 0 off the eye
  input.add(glm::vec4(0, 0, 0, 0), glm::vec4(1, 0, 0, 0), glm::vec4(0, 1, 0, 0));  // all w = 0
  input.add(a, b, glm::vec4(0.0f, 0.5f, -0.5f, -1.0f));                     // one vertex behind the eye
  input.add(a * -1.0f, b * -1.0f, c * -1.0f);                               // all w < 0, z < 0: behind
  input.add(glm::vec4(-0.5f, -0.5f, 0.5f, -1.0f), glm::vec4(0.5f, -0.5f, 0.5f, -1.0f),
            glm::vec4(0.0f, 0.5f, 0.5f, -1.0f));                            // w < 0 with z > 0
  input.add(a, b, glm::vec4(1e30f, 0.0f, 0.5f, 1.0f));                      // huge x
  input.add(a, glm::vec4(-1e30f, 1e30f, 0.5f, 1.0f), glm::vec4(1e30f, 1e30f, 0.5f, 1.0f));
  input.add(a, b, glm::vec4(0.0f, 0.0f, 1e30f, 1e30f));                     // huge z and w
  input.add(a, b, glm::vec4(3e38f, 0.0f, 0.5f, 3e38f));                     // 4 * w overflows to inf
  input.add(a, b, glm::vec4(0.0f, -3e38f, 0.5f, 1.0f));
  input.add(glm::vec4(-1e-30f, -1e-30f, 1e-31f, 1e-30f), glm::vec4(1e-30f, -1e-30f, 1e-31f, 1e-30f),
            glm::vec4(0.0f, 1e-30f, 1e-31f, 1e-30f));                       // tiny w: the usual screen
  input.add(a, b, c);                                                        // a plain one
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kSize, kSize);
  for (const gpu::SetupTriangle& s : setup) EXPECT_GE(s.triangle, firstFinite) << describe(s);
  for (VisibilityScheme scheme : kSchemes) {
    const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
    for (const gpu::SetupTriangle& s : v.setup) {
      EXPECT_GE(s.triangle, firstFinite) << "non-finite input was set up: " << describe(s);
      EXPECT_TRUE(std::isfinite(s.p0.x) && std::isfinite(s.p0.y) && std::isfinite(s.p1.x) && std::isfinite(s.p1.y) &&
                  std::isfinite(s.p2.x) && std::isfinite(s.p2.y))
          << describe(s);
      EXPECT_TRUE(s.pixelBounds.z < kSize && s.pixelBounds.w < kSize) << describe(s);
    }
  }
  expectMatchesReference(input, kSize, kSize, 1.0);
}

// Independent of the reference: a spike from (-0.5, -0.5)-(0.5, -0.5) (NDC) to a vertex
// straight up at y = -far must cover the top of the screen between x = -0.45 and 0.45, however
// far away that vertex is (its guard-band intersection lies at y = -4, off screen).
TEST_F(RasterizeKernelTest, HugeCoordinatesKeepTheVisiblePart) {
  constexpr uint32_t kSize = 32;
  for (float far : {1e3f, 1e6f, 1e10f, 1e30f, 3e38f}) {
    std::ostringstream trace;
    trace << "far vertex at y = " << -far;
    SCOPED_TRACE(trace.str());
    ClipTriangles input;
    input.add(glm::vec4(-0.5f, -0.5f, 0.5f, 1.0f), glm::vec4(0.5f, -0.5f, 0.5f, 1.0f),
              glm::vec4(0.0f, -far, 0.5f, 1.0f));
    for (VisibilityScheme scheme : kSchemes) {
      SCOPED_TRACE(passes::visibilitySchemeName(scheme));
      const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
      size_t missing = 0;
      std::ostringstream where;
      for (uint32_t y = 0; y <= 6; ++y) {     // NDC y from -0.97 to -0.59
        for (uint32_t x = 9; x <= 22; ++x) {  // NDC x from -0.41 to 0.41
          if (v.idAt(x, y) == 0u) continue;
          if (missing++ < 8) where << " (" << x << ", " << y << ")";
        }
      }
      EXPECT_EQ(missing, 0u) << "of the 98 pixel centres inside the visible part of the spike are not covered:"
                             << where.str();
    }
  }
}

// GLSL round() of a vertex exactly halfway between two 1/256 sub-pixel steps: the reference
// rounds half to even as lavapipe does; a kernel or driver rounding otherwise shows here.
TEST_F(RasterizeKernelTest, HalfSubpixelVerticesSnapLikeTheReference) {
  constexpr uint32_t kSize = 16;
  constexpr float kHalfStep = 1.0f / 512.0f;
  auto at = [&](float x, float y) { return atScreen(x, y, 0.5f, kSize, kSize); };
  ClipTriangles input;
  input.add(at(3.0f + kHalfStep, 2.0f + 3 * kHalfStep), at(12.0f + 3 * kHalfStep, 2.0f + kHalfStep),
            at(3.0f + 5 * kHalfStep, 13.0f + 7 * kHalfStep));
  input.add(at(0.5f - kHalfStep, 0.5f + kHalfStep), at(15.5f + kHalfStep, 0.5f - kHalfStep),
            at(0.5f + kHalfStep, 15.5f - kHalfStep), true);
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kSize, kSize);
  ASSERT_EQ(setup.size(), 2u);
  EXPECT_EQ(setup[0].p0.x, 3.0f) << "768.5 / 256 rounds half to even";
  expectMatchesReference(input, kSize, kSize, 1.0);
}

TEST_F(RasterizeKernelTest, TrianglesBehindTheCameraDrawNothing) {
  constexpr uint32_t kSize = 16;
  ClipTriangles input;
  // A camera-space triangle behind the eye: w < 0 and z < 0 (both outside the near plane).
  input.add(glm::vec4(-0.5f, -0.5f, -1.2f, -1.0f), glm::vec4(0.5f, -0.5f, -1.2f, -1.0f),
            glm::vec4(0.0f, 0.5f, -1.2f, -1.0f));
  // z < 0 with w > 0: in front of the eye but nearer than the near plane.
  input.add(glm::vec4(-0.5f, -0.5f, -0.1f, 1.0f), glm::vec4(0.5f, -0.5f, -0.1f, 1.0f),
            glm::vec4(0.0f, 0.5f, -0.1f, 1.0f));
  for (VisibilityScheme scheme : kSchemes) {
    const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
    EXPECT_EQ(v.stats.setupTriangles, 0u);
    for (const glm::uvec2& e : v.entries) EXPECT_EQ(e, glm::uvec2(HMB_VIS_EMPTY));
  }
  expectMatchesReference(input, kSize, kSize, 1.0);
}

// A triangle crossing the near plane: only the part with z >= 0 remains (split in two).
TEST_F(RasterizeKernelTest, NearPlaneCrossingKeepsTheFrontPart) {
  constexpr uint32_t kSize = 32;
  ClipTriangles input;
  // Depth is reversed: z > w lies in front of the near plane.
  input.add(glm::vec4(-0.75f, -0.75f, 0.5f, 1.0f), glm::vec4(0.75f, -0.75f, 1.5f, 1.0f),
            glm::vec4(0.0f, 0.75f, 1.5f, 1.0f));
  input.add(glm::vec4(-2.0f, 1.0f, 3.0f, 2.0f), glm::vec4(2.0f, 1.0f, 1.0f, 2.0f), glm::vec4(0.0f, 2.0f, 0.0f, 0.5f));
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kSize, kSize);
  ASSERT_GE(setup.size(), 3u) << "near clipping turns the first triangle into a quad: two triangles";
  const reference::ReferenceVisibility expected = reference::rasterizeReference(setup, kSize, kSize);
  size_t covered = 0;
  for (const glm::uvec2& e : expected.entries) covered += e.x != HMB_VIS_EMPTY;
  EXPECT_GT(covered, 50u);
  expectMatchesReference(input, kSize, kSize, 1.0);
}

// Depths exactly 0 (z = 0, on the far plane) and 1 (z = w, on the near plane: depth is
// reversed) are inside the depth range; a triangle whose depth passes below 0 is drawn only
// where it is >= 0.
TEST_F(RasterizeKernelTest, DepthRangeEndsAreInclusive) {
  constexpr uint32_t kSize = 16;
  ClipTriangles input;
  input.add(atScreen(0.5f, 0.5f, 0.0f, kSize, kSize), atScreen(8.5f, 0.5f, 0.0f, kSize, kSize),
            atScreen(0.5f, 8.5f, 0.0f, kSize, kSize));
  input.add(atScreen(16, 8, 1.0f, kSize, kSize), atScreen(16, 16, 1.0f, kSize, kSize),
            atScreen(8, 16, 1.0f, kSize, kSize));
  input.add(atScreen(0, 10, 0.5f, kSize, kSize), atScreen(8, 10, -0.5f, kSize, kSize),
            atScreen(0, 16, 0.5f, kSize, kSize));
  for (VisibilityScheme scheme : kSchemes) {
    SCOPED_TRACE(passes::visibilitySchemeName(scheme));
    const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
    EXPECT_EQ(v.idAt(0, 0), 0u);
    EXPECT_EQ(v.depthAt(0, 0), 0.0f);
    EXPECT_EQ(v.idAt(15, 15), 1u);
    EXPECT_EQ(v.depthAt(15, 15), 1.0f);
    EXPECT_EQ(v.idAt(0, 12), 2u);              // depth 0.4375 there
    EXPECT_EQ(v.idAt(6, 10), HMB_VIS_EMPTY);   // depth -0.31 there: beyond the far plane
  }
  expectMatchesReference(input, kSize, kSize, 1.0);
}

// Sub-pixel triangles between pixel centres set up nothing (empty pixel bounds); one around a
// centre covers exactly that pixel.
TEST_F(RasterizeKernelTest, SubPixelTrianglesCoverOnlyTheCentresInside) {
  constexpr uint32_t kSize = 8;
  auto at = [&](float x, float y) { return atScreen(x, y, 0.5f, kSize, kSize); };
  ClipTriangles input;
  input.add(at(3.6f, 3.6f), at(3.9f, 3.6f), at(3.6f, 3.9f));           // inside one pixel, off the centre
  input.add(at(4.51f, 2.1f), at(4.99f, 2.1f), at(4.99f, 2.45f));        // right of a centre
  input.add(at(1.0f, 1.0f), at(1.49f, 1.0f), at(1.0f, 1.49f));          // just short of the centre (1.5, 1.5)
  input.add(at(5.25f, 5.25f), at(5.75f, 5.375f), at(5.375f, 5.75f));    // around the centre (5.5, 5.5)
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(input.clip, input.triangles, input.doubleSided, kSize, kSize);
  ASSERT_EQ(setup.size(), 1u);
  for (VisibilityScheme scheme : kSchemes) {
    SCOPED_TRACE(passes::visibilitySchemeName(scheme));
    const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
    for (uint32_t y = 0; y < kSize; ++y)
      for (uint32_t x = 0; x < kSize; ++x)
        EXPECT_EQ(v.idAt(x, y), (x == 5 && y == 5) ? 3u : HMB_VIS_EMPTY) << "pixel (" << x << ", " << y << ")";
  }
  expectMatchesReference(input, kSize, kSize, 1.0);
}

// A triangle covering the whole 1024x1024 screen (many more tiles than HMB_RASTER_LARGE_TILES)
// goes through bin_large_triangles; a tilted one with varying w in front of part of it.
TEST_F(RasterizeKernelTest, ScreenCoveringTriangleUsesLargeBinning) {
  constexpr uint32_t kSize = 1024;
  ClipTriangles input;
  input.add(glm::vec4(-1.0f, -1.0f, 0.75f, 1.0f), glm::vec4(3.0f, -1.0f, 0.75f, 1.0f),
            glm::vec4(-1.0f, 3.0f, 0.75f, 1.0f));
  input.add(glm::vec4(-0.5f, -1.0f, 0.25f, 0.5f), glm::vec4(4.0f, 0.0f, 0.5f, 2.0f), glm::vec4(0.0f, 4.0f, 1.0f, 4.0f));
  for (VisibilityScheme scheme : kSchemes) {
    const Visibility v = rasterizeClipTriangles(context(), input, kSize, kSize, scheme);
    EXPECT_EQ(v.stats.largeTriangles, 2u);
    size_t empty = 0;
    for (const glm::uvec2& e : v.entries) empty += e.x == HMB_VIS_EMPTY;
    EXPECT_EQ(empty, 0u) << "the first triangle covers every pixel";
  }
  const double agreement = expectMatchesReference(input, kSize, kSize, 1.0);
  RecordProperty("id_agreement_1024x1024", std::to_string(agreement));
}

// Equal depths resolve to the smallest id, in both schemes: 20 copies of a screen-covering quad
// (ids 8..47) hide the small triangles drawn after them (ids 48..55) and lose to the ones
// before them (ids 0..7).
TEST_F(RasterizeKernelTest, EqualDepthOverlapsResolveToSmallestId) {
  constexpr uint32_t kWidth = 24, kHeight = 20;
  auto at = [&](float x, float y) { return atScreen(x, y, 0.5f, kWidth, kHeight, 2.0f); };
  auto addSmall = [&](ClipTriangles& input, int k) {
    const float x = 2.0f + float(k % 4) * 5.0f, y = 2.0f + float(k / 4 % 2) * 8.0f;
    input.add(at(x, y), at(x + 6.5f, y + 1.0f), at(x + 2.0f, y + 7.5f));
  };
  ClipTriangles input;
  for (int k = 0; k < 8; ++k) addSmall(input, k);
  for (int copy = 0; copy < 20; ++copy) {
    input.add(at(-4, -4), at(30, -4), at(30, 30));
    input.add(at(-4, -4), at(30, 30), at(-4, 30));
  }
  for (int k = 0; k < 8; ++k) addSmall(input, k + 3);
  for (VisibilityScheme scheme : kSchemes) {
    SCOPED_TRACE(passes::visibilitySchemeName(scheme));
    const Visibility v = rasterizeClipTriangles(context(), input, kWidth, kHeight, scheme);
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        const uint32_t id = v.idAt(x, y);
        EXPECT_TRUE(id < 10u) << "pixel (" << x << ", " << y << ") shows triangle " << id;
        EXPECT_EQ(v.depthAt(x, y), 0.5f);
      }
  }
  expectMatchesReference(input, kWidth, kHeight, 1.0);
}

// The reference itself, on a hand-checked case, so a reference bug cannot hide a kernel bug.
TEST(RasterReferenceTest, CoverageDepthOfAHandCheckedTriangle) {
  gpu::SetupTriangle s{};
  // Positive area in y-down pixels (the setup's output orientation).
  s.p0 = {0.5f, 0.5f};
  s.p1 = {4.5f, 0.5f};
  s.p2 = {0.5f, 4.5f};
  s.depth = {0.0f, 1.0f, 0.5f, 0.0f};
  s.pixelBounds = {0, 0, 4, 4};
  ASSERT_GT((s.p1.x - s.p0.x) * (s.p2.y - s.p0.y) - (s.p1.y - s.p0.y) * (s.p2.x - s.p0.x), 0.0f);
  EXPECT_EQ(reference::coverageDepth(s, {0, 0}), 0.0f);   // vertex on the top and left edges
  EXPECT_EQ(reference::coverageDepth(s, {0, 2}), 0.25f);  // on the left edge: owned
  EXPECT_EQ(reference::coverageDepth(s, {2, 0}), 0.5f);   // on the top edge: owned
  EXPECT_EQ(reference::coverageDepth(s, {1, 1}), 0.375f);
  EXPECT_EQ(reference::coverageDepth(s, {2, 2}), -1.0f);  // on the diagonal (a bottom-right edge)
  EXPECT_EQ(reference::coverageDepth(s, {0, 4}), -1.0f);
  EXPECT_EQ(reference::tilesAcross(17), 3u);
  s.pixelBounds = {7, 3, 17, 9};
  EXPECT_EQ(reference::triangleTiles(s, 3), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
}

}  // namespace
}  // namespace hmb::test
