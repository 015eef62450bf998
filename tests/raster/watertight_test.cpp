// Watertightness: a mesh covering the whole screen at one plane depth must cover every pixel
// centre exactly once (no holes along shared edges, no double hits), through near-plane /
// guard-band clipping, snapping and the top-left rule, in both visibility schemes.
//
// atomicMin hides double hits, so each mesh is rendered twice, the second time with the
// triangle ids reversed (id' = N - 1 - id): at equal depth the smallest id wins, so a centre
// covered by two triangles shows a different triangle in the two renders, while a centre
// covered once shows the same one. The depth is 0.5 everywhere (z = w / 2 at every vertex),
// so no depth difference can decide a double hit instead of the ids. It is exactly 0.5 where a
// device divides exactly (lavapipe does); elsewhere it is within the bound Vulkan's precision
// rules give z / w ("Precision and Operation of SPIR-V Instructions": a division within 2.5 ULP;
// equal vertex depths then interpolate within one more), and a last-bit depth difference may
// decide a double hit unseen. The reference's coverage count must be 1 everywhere too.
#include <cmath>
#include <numbers>
#include <ostream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/raster/raster_harness.h"
#include "tests/raster/raster_reference.h"
#include "tests/support/vulkan_precision.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using passes::VisibilityScheme;

enum class Mesh { JitteredGrid, Fan, FanThroughNearPlane };

struct WatertightCase {
  Mesh mesh;
  bool perspective;  // w varies per vertex
  uint32_t width, height;
  VisibilityScheme scheme;
};

std::string caseName(const WatertightCase& c) {
  const char* mesh = c.mesh == Mesh::JitteredGrid ? "grid" : c.mesh == Mesh::Fan ? "fan" : "near_fan";
  std::string name = std::string(mesh) +
                     (c.perspective ? "_perspective_" : "_flat_") + std::to_string(c.width) + "x" +
                     std::to_string(c.height) + "_" + passes::visibilitySchemeName(c.scheme);
  for (char& ch : name)
    if (ch == '-') ch = '_';
  return name;
}

void PrintTo(const WatertightCase& c, std::ostream* os) { *os << caseName(c); }

// The clip-space vertex (x, y, w / 2, w): depth z/w = 0.5 (w / 2 is exact, and so is the quotient
// where the division is correctly rounded).
glm::vec4 onPlane(double x, double y, double w) {
  const float fw = float(w);
  return {float(x), float(y), 0.5f * fw, fw};
}

// Signed area of the triangle in NDC, whose y points down the image like pixel rows: front faces
// (kept when single-sided) have negative area.
double ndcArea(glm::vec4 a, glm::vec4 b, glm::vec4 c) {
  const double ax = double(a.x) / a.w, ay = double(a.y) / a.w;
  const double bx = double(b.x) / b.w, by = double(b.y) / b.w;
  const double cx = double(c.x) / c.w, cy = double(c.y) / c.w;
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}

// 64 x 64 quads over the screen and past it, interior vertices jittered by up to 0.3 cell,
// each quad split along a random diagonal; front faces, single-sided.
ClipTriangles jitteredGrid(uint32_t seed, bool perspective) {
  constexpr int kCells = 64;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<glm::vec4> points;
  for (int j = 0; j <= kCells; ++j) {
    for (int i = 0; i <= kCells; ++i) {
      double u = -1.0 + 2.0 * i / kCells, v = -1.0 + 2.0 * j / kCells;
      if (i > 0 && i < kCells && j > 0 && j < kCells) {
        u += jitter(rng) * 2.0 / kCells;
        v += jitter(rng) * 2.0 / kCells;
      }
      if (perspective) {
        // A plane seen at a grazing angle: w from 0.15 to 0.95, NDC x from -13 to 2.1 (the
        // far-off part is rejected by the frustum test, cells shrink from left to right).
        const double gx = 2.0 * u, gy = 2.0 * v;
        points.push_back(onPlane(gx, gy, 0.15 + 0.2 * (gx + 2.0)));
      } else {
        points.push_back(onPlane(1.2 * u, 1.2 * v, 1.0));
      }
    }
  }
  ClipTriangles mesh;
  auto at = [&](int i, int j) { return points[size_t(j) * (kCells + 1) + i]; };
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      const glm::vec4 p00 = at(i, j), p10 = at(i + 1, j), p11 = at(i + 1, j + 1), p01 = at(i, j + 1);
      if (rng() % 2 == 0) {
        mesh.add(p00, p11, p10, false);
        mesh.add(p00, p01, p11, false);
      } else {
        mesh.add(p00, p01, p10, false);
        mesh.add(p10, p01, p11, false);
      }
    }
  }
  return mesh;
}

// 200 thin triangles around one centre point, out to a jittered rim of radius 6 NDC (past the
// guard band, so every triangle is clipped); front faces, single-sided.
// throughNearPlane: every rim vertex lies behind the eye (w < 0, so z = w / 2 < 0) at the
// point opposite the centre, so each triangle is cut by the near plane and its visible part is
// the wedge from the centre towards the rim direction, out to infinity (then the guard band):
// the wedges still tile the screen.
ClipTriangles fan(uint32_t seed, bool perspective, bool throughNearPlane = false) {
  constexpr int kTriangles = 200;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3), wRange(0.5, 2.0);
  const double cx = 0.13, cy = -0.21;
  auto vertex = [&](double x, double y, bool behind) {
    const double w = (perspective ? wRange(rng) : 1.0) * (behind ? -1.0 : 1.0);
    return onPlane(x * w, y * w, w);
  };
  const glm::vec4 centre = vertex(cx, cy, false);
  std::vector<glm::vec4> rim;
  for (int k = 0; k < kTriangles; ++k) {
    const double angle = 2.0 * std::numbers::pi * (k + jitter(rng)) / kTriangles;
    const double side = throughNearPlane ? -1.0 : 1.0;
    rim.push_back(vertex(cx + side * 6.0 * std::cos(angle), cy + side * 6.0 * std::sin(angle), throughNearPlane));
  }
  ClipTriangles mesh;
  for (int k = 0; k < kTriangles; ++k) mesh.add(centre, rim[(k + 1) % kTriangles], rim[k], false);
  return mesh;
}

// The same triangles with ids reversed: triangle N - 1 - t of the result is triangle t.
ClipTriangles reversedIds(const ClipTriangles& input) {
  ClipTriangles out = input;
  out.triangles.assign(input.triangles.rbegin(), input.triangles.rend());
  return out;
}

struct CoverageFaults {
  size_t holes = 0, doubleHits = 0, offPlane = 0;
  std::string where;  // the first few, for the failure message
};

// How far from 0.5 a pixel's depth may be: each vertex's z / w within a division's bound, and
// the interpolation of the three within one more rounding.
constexpr uint32_t kPlaneDepthUlp = kVulkanDivisionUlp + 1;

// Counts pixels covered by no triangle, by several (different winners in the render and its
// id-reversed copy), or at a depth off 0.5 by more than kPlaneDepthUlp.
CoverageFaults coverageFaults(const Visibility& forward, const Visibility& backward, uint32_t n) {
  CoverageFaults f;
  std::ostringstream where;
  int listed = 0;
  for (uint32_t y = 0; y < forward.height; ++y) {
    for (uint32_t x = 0; x < forward.width; ++x) {
      const uint32_t a = forward.idAt(x, y), b = backward.idAt(x, y);
      if (a == HMB_VIS_EMPTY || b == HMB_VIS_EMPTY) {
        ++f.holes;
        if (listed++ < 6) where << "\n  hole at (" << x << ", " << y << ")";
      } else if (a != n - 1 - b) {
        ++f.doubleHits;
        if (listed++ < 6)
          where << "\n  (" << x << ", " << y << ") covered by triangles " << a << " and " << n - 1 - b;
      }
      f.offPlane += a != HMB_VIS_EMPTY && ulpDistance(forward.depthAt(x, y), 0.5f) > kPlaneDepthUlp;
    }
  }
  f.where = where.str();
  return f;
}

// Renders the mesh and its id-reversed copy and counts their faults.
CoverageFaults renderAndCount(const ClipTriangles& mesh, uint32_t width, uint32_t height, VisibilityScheme scheme) {
  const Visibility forward = rasterizeClipTriangles(VulkanTest::context(), mesh, width, height, scheme);
  const Visibility backward = rasterizeClipTriangles(VulkanTest::context(), reversedIds(mesh), width, height, scheme);
  return coverageFaults(forward, backward, static_cast<uint32_t>(mesh.triangles.size()));
}

class WatertightTest : public VulkanTest, public ::testing::WithParamInterface<WatertightCase> {};

TEST_P(WatertightTest, EveryPixelCentreIsCoveredExactlyOnce) {
  const WatertightCase& c = GetParam();
  const ClipTriangles mesh = c.mesh == Mesh::JitteredGrid ? jitteredGrid(7u, c.perspective)
                             : c.mesh == Mesh::Fan       ? fan(11u, c.perspective)
                                                         : fan(13u, c.perspective, true);
  const auto n = static_cast<uint32_t>(mesh.triangles.size());
  // The premise: every triangle is a front face, so none is culled and none overlaps another.
  for (uint32_t t = 0; t < n; ++t) {
    const gpu::GpuTriangle& tri = mesh.triangles[t];
    ASSERT_LT(ndcArea(mesh.clip[tri.v0], mesh.clip[tri.v1], mesh.clip[tri.v2]), 0.0) << "triangle " << t;
  }

  const Visibility forward = rasterizeClipTriangles(context(), mesh, c.width, c.height, c.scheme);
  const Visibility backward = rasterizeClipTriangles(context(), reversedIds(mesh), c.width, c.height, c.scheme);
  const CoverageFaults f = coverageFaults(forward, backward, n);
  EXPECT_EQ(f.holes, 0u) << f.where;
  EXPECT_EQ(f.doubleHits, 0u) << f.where;
  EXPECT_EQ(f.offPlane, 0u) << "pixels whose depth is off 0.5 by more than the division allows (the double-hit "
                               "check relies on equal depths)";

  // The reference's own count, which also sees double hits within one clipped triangle's fan.
  const std::vector<gpu::SetupTriangle> setup =
      reference::setupTriangles(mesh.clip, mesh.triangles, mesh.doubleSided, c.width, c.height);
  if (c.mesh != Mesh::JitteredGrid) {
    std::set<uint32_t> ids;
    for (const gpu::SetupTriangle& s : setup) ids.insert(s.triangle);
    EXPECT_GT(setup.size(), ids.size()) << "the guard band should split triangles of this mesh";
  }
  const reference::ReferenceVisibility expected = reference::rasterizeReference(setup, c.width, c.height);
  size_t notOnce = 0, sameIds = 0;
  for (size_t i = 0; i < expected.coverage.size(); ++i) {
    notOnce += expected.coverage[i] != 1u;
    sameIds += expected.entries[i].x == forward.entries[i].x;
  }
  EXPECT_EQ(notOnce, 0u) << "pixel centres the reference covers zero or several times";
  const double agreement = double(sameIds) / double(expected.coverage.size());
  RecordProperty("id_agreement", std::to_string(agreement));
  EXPECT_GE(agreement, 0.999) << "kernel and reference disagree on the covering triangle";
}

// The checks above can fail: a missing triangle leaves holes, an extra copy of one (at the
// same depth) double-covers its pixels.
class WatertightCheckTest : public VulkanTest {};

TEST_F(WatertightCheckTest, SeesHolesAndDoubleHits) {
  constexpr uint32_t kWidth = 301, kHeight = 157;
  const ClipTriangles mesh = jitteredGrid(7u, false);
  // The triangle the reference sees at the centre of the screen: it covers at least that pixel.
  const reference::ReferenceVisibility expected = reference::rasterizeReference(
      reference::setupTriangles(mesh.clip, mesh.triangles, mesh.doubleSided, kWidth, kHeight), kWidth, kHeight);
  const uint32_t victim = expected.idAt(kWidth / 2, kHeight / 2);
  ASSERT_LT(victim, mesh.triangles.size());
  ClipTriangles missing = mesh;
  missing.triangles.erase(missing.triangles.begin() + victim);
  ClipTriangles extra = mesh;
  extra.triangles.insert(extra.triangles.begin() + 100, mesh.triangles[victim]);
  for (VisibilityScheme scheme : {VisibilityScheme::Int64Atomics, VisibilityScheme::Depth32TwoPass, VisibilityScheme::TileLists}) {
    SCOPED_TRACE(passes::visibilitySchemeName(scheme));
    const CoverageFaults withHole = renderAndCount(missing, kWidth, kHeight, scheme);
    EXPECT_GT(withHole.holes, 0u);
    EXPECT_EQ(withHole.doubleHits, 0u);
    const CoverageFaults withOverlap = renderAndCount(extra, kWidth, kHeight, scheme);
    EXPECT_EQ(withOverlap.holes, 0u);
    EXPECT_GT(withOverlap.doubleHits, 0u);
  }
}

std::vector<WatertightCase> watertightCases() {
  std::vector<WatertightCase> cases;
  for (Mesh mesh : {Mesh::JitteredGrid, Mesh::Fan, Mesh::FanThroughNearPlane})
    for (bool perspective : {false, true})
      for (auto [width, height] : {std::pair<uint32_t, uint32_t>{301, 157}, {67, 43}})
        for (VisibilityScheme scheme : {VisibilityScheme::Int64Atomics, VisibilityScheme::Depth32TwoPass, VisibilityScheme::TileLists})
          cases.push_back({mesh, perspective, width, height, scheme});
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Meshes, WatertightTest, ::testing::ValuesIn(watertightCases()),
                         [](const ::testing::TestParamInfo<WatertightCase>& info) { return caseName(info.param); });

}  // namespace
}  // namespace hmb::test
