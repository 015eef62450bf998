// Where a method's error comes from (runtime/metrics/error_sources.h), on images made here:
// each class where its rule puts it (curved paths first, then the pixel's own motion split by
// the ray mask, then motion near it, then nothing), the shares of the squared error, the
// reference's noise from two halves, and the checks on sizes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "hmblur/error.h"
#include "runtime/metrics/error_sources.h"

namespace hmb::metrics {
namespace {

constexpr uint32_t kW = 40, kH = 10;

DisplayImage flat(float value) {
  return DisplayImage{kW, kH, std::vector<float>(size_t(kW) * kH * 3, value)};
}

size_t at(uint32_t x, uint32_t y) { return size_t(y) * kW + x; }

// A row of test pixels, each with its own situation, and the error each one carries.
struct Fixture {
  DisplayImage reference = flat(0.5f), test = flat(0.5f);
  BlurRegion region{kW, kH, std::vector<uint8_t>(size_t(kW) * kH, 0), 0};
  std::vector<float> length = std::vector<float>(size_t(kW) * kH, 0.0f);
  std::vector<float> bend = std::vector<float>(size_t(kW) * kH, 0.0f);
  std::vector<uint32_t> mask = std::vector<uint32_t>(size_t(kW) * kH, 0u);

  void wrong(uint32_t x, uint32_t y, float by) {
    region.inside[at(x, y)] = 1;
    ++region.pixelCount;
    for (int c = 0; c < 3; ++c) test.rgb[3 * at(x, y) + c] = 0.5f + by;
  }
  ErrorSources explain(bool withMask, std::span<const float> noise = {}) const {
    ErrorSourceInputs in;
    in.reference = &reference;
    in.test = &test;
    in.region = &region;
    in.pathLength = length;
    in.pathBend = bend;
    if (withMask) in.rayMask = mask;
    in.referenceNoise = noise;
    return explainErrorSources(in);
  }
};

TEST(ErrorSourcesTest, EachPixelGoesToTheFirstClassWhoseRuleHolds) {
  Fixture f;
  // A mover 3 pixels long at x = 5..7 (its pixels traced by the mask at 5 and 6), so "near" is
  // 3 pixels: x = 9 and 10 are near it, x = 11 is not.
  for (uint32_t x = 5; x <= 7; ++x) f.length[at(x, 4)] = 3.0f;
  f.mask[at(5, 4)] = f.mask[at(6, 4)] = 1u;
  f.wrong(5, 4, 0.1f);   // inner, traced
  f.wrong(7, 4, 0.2f);   // inner, not traced
  f.wrong(10, 4, 0.1f);  // outer: a mover 3 pixels away
  f.wrong(11, 4, 0.1f);  // other: the nearest mover is 4 pixels away
  // A path that bends 0.6 pixels at x = 30: it and its neighbours within reach are curved,
  // whatever else holds there.
  f.bend[at(30, 4)] = 0.6f;
  f.length[at(30, 4)] = 1.0f;
  f.mask[at(31, 4)] = 1u;
  f.wrong(30, 4, 0.3f);
  f.wrong(33, 4, 0.3f);
  f.wrong(34, 4, 0.3f);  // 4 pixels off: not near
  const ErrorSources s = f.explain(true);
  EXPECT_EQ(s.reachPixels, 3u);
  EXPECT_EQ(s.perPixel[at(5, 4)], ErrorSource::InnerTraced);
  EXPECT_EQ(s.perPixel[at(7, 4)], ErrorSource::InnerNotTraced);
  EXPECT_EQ(s.perPixel[at(10, 4)], ErrorSource::OuterBlur);
  EXPECT_EQ(s.perPixel[at(11, 4)], ErrorSource::Other);
  EXPECT_EQ(s.perPixel[at(30, 4)], ErrorSource::CurvedPath);
  EXPECT_EQ(s.perPixel[at(33, 4)], ErrorSource::CurvedPath);
  EXPECT_EQ(s.perPixel[at(34, 4)], ErrorSource::Other);
  EXPECT_EQ(s.perPixel[at(6, 4)], ErrorSource::Outside);  // no error there: not in the region
  // Near reaches along y as well (a square window).
  Fixture g;
  g.length[at(20, 1)] = 2.0f;
  g.wrong(21, 3, 0.1f);
  g.wrong(20, 4, 0.1f);
  const ErrorSources t = g.explain(false);
  EXPECT_EQ(t.perPixel[at(21, 3)], ErrorSource::OuterBlur);
  EXPECT_EQ(t.perPixel[at(20, 4)], ErrorSource::Other);

  // Without a ray mask every moving pixel is inner blur not traced.
  const ErrorSources noMask = f.explain(false);
  EXPECT_EQ(noMask.perPixel[at(5, 4)], ErrorSource::InnerNotTraced);
}

TEST(ErrorSourcesTest, SharesAreEachClasssPartOfTheSquaredError) {
  Fixture f;
  f.length[at(5, 4)] = 2.0f;
  f.wrong(5, 4, 0.2f);   // inner: 0.04
  f.wrong(6, 4, 0.1f);   // outer: 0.01
  f.wrong(7, 4, -0.1f);  // outer: 0.01
  f.wrong(20, 4, 0.1f);  // other: 0.01
  std::vector<float> noise(size_t(kW) * kH, 0.0f);
  noise[at(5, 4)] = 0.001f;
  noise[at(20, 4)] = 0.002f;
  noise[at(0, 0)] = 1.0f;  // outside the region: not counted
  const ErrorSources s = f.explain(false, noise);
  EXPECT_EQ(s.regionPixels, 4u);
  EXPECT_NEAR(s.squaredError, 0.07, 1e-6);
  ASSERT_EQ(s.rows.size(), kErrorSources.size());
  double shares = 0.0;
  for (const ErrorSourceRow& row : s.rows) shares += row.share;
  EXPECT_NEAR(shares, 1.0, 1e-9);
  const auto row = [&](ErrorSource source) { return s.rows[size_t(source) - 1]; };
  EXPECT_EQ(row(ErrorSource::InnerNotTraced).pixels, 1u);
  EXPECT_NEAR(row(ErrorSource::InnerNotTraced).share, 0.04 / 0.07, 1e-6);
  EXPECT_EQ(row(ErrorSource::OuterBlur).pixels, 2u);
  EXPECT_NEAR(row(ErrorSource::OuterBlur).share, 0.02 / 0.07, 1e-6);
  EXPECT_NEAR(row(ErrorSource::Other).share, 0.01 / 0.07, 1e-6);
  EXPECT_EQ(row(ErrorSource::CurvedPath).pixels, 0u);
  ASSERT_TRUE(s.noise && row(ErrorSource::Other).noise);
  EXPECT_NEAR(*s.noise, 0.003, 1e-7);
  EXPECT_NEAR(*row(ErrorSource::Other).noise, 0.002, 1e-7);
  EXPECT_FALSE(f.explain(false).noise);

  const nlohmann::json json = errorSourcesJson(s);
  EXPECT_EQ(json["region_pixels"], 4);
  EXPECT_EQ(json["classes"].size(), kErrorSources.size());
  EXPECT_EQ(json["classes"][2]["class"], "inner-not-traced");

  // An image with no error has no shares, and says so with zeros.
  Fixture none;
  const ErrorSources empty = none.explain(false);
  EXPECT_EQ(empty.regionPixels, 0u);
  for (const ErrorSourceRow& r : empty.rows) EXPECT_EQ(r.share, 0.0);
}

TEST(ErrorSourcesTest, PathsBehindTheCameraCountAsCurved) {
  Fixture f;
  f.length[at(3, 3)] = f.bend[at(3, 3)] = INFINITY;
  f.wrong(3, 3, 0.1f);
  f.wrong(4, 3, 0.1f);
  const ErrorSources s = f.explain(false);
  EXPECT_EQ(s.perPixel[at(3, 3)], ErrorSource::CurvedPath);
  EXPECT_EQ(s.reachPixels, 0u);  // infinite lengths do not set the reach
  EXPECT_EQ(s.perPixel[at(4, 3)], ErrorSource::Other);
}

TEST(ErrorSourcesTest, TheReferencesNoiseIsAQuarterOfItsHalvesSquaredDifference) {
  DisplayImage a = flat(0.5f), b = flat(0.5f);
  a.rgb[3 * at(2, 2)] = 0.8f;  // red differs by 0.3: (0.09 / 3) / 4
  const std::vector<float> noise = referenceNoise(a, b);
  EXPECT_NEAR(noise[at(2, 2)], 0.09 / 12.0, 1e-7);
  EXPECT_EQ(noise[at(3, 2)], 0.0f);
  EXPECT_THROW(referenceNoise(a, DisplayImage{kW, kH + 1, std::vector<float>(size_t(kW) * (kH + 1) * 3)}), Error);
}

TEST(ErrorSourcesTest, ImagesOfAnotherSizeAreRefused) {
  Fixture f;
  f.length.pop_back();
  EXPECT_THROW(f.explain(false), Error);
  Fixture g;
  g.mask.pop_back();
  EXPECT_THROW(g.explain(true), Error);
  EXPECT_NO_THROW(g.explain(false));
}

TEST(ErrorSourcesTest, TheImageColoursEachClassOverADimReference) {
  Fixture f;
  f.length[at(5, 4)] = 2.0f;
  f.wrong(5, 4, 0.1f);
  const ErrorSources s = f.explain(false);
  const io::Rgba8Image image = errorSourceImage(s, f.reference);
  const std::array<uint8_t, 3> inner = errorSourceColor(ErrorSource::InnerNotTraced);
  for (size_t c = 0; c < 3; ++c) EXPECT_EQ(image.pixels[4 * at(5, 4) + c], inner[c]);
  // Outside: the reference's luma, dimmed to at most 90 of 255.
  EXPECT_LE(image.pixels[4 * at(0, 0)], 90);
  EXPECT_EQ(image.pixels[4 * at(0, 0)], image.pixels[4 * at(0, 0) + 1]);
  for (const ErrorSource a : kErrorSources)
    for (const ErrorSource b : kErrorSources) {
      if (a != b) {
        EXPECT_NE(errorSourceColor(a), errorSourceColor(b)) << errorSourceName(a);
      }
    }
}

}  // namespace
}  // namespace hmb::metrics
