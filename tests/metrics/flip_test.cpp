#include <gtest/gtest.h>

#include <cmath>

#include "runtime/metrics/metrics.h"
#include "tests/metrics/metrics_test_images.h"

namespace hmb::metrics {
namespace {

using testing::constantImage;
using testing::patternImage;
using testing::randomImage;
using testing::withNoise;

double meanFlip(const DisplayImage& a, const DisplayImage& b, float ppd = kDefaultPixelsPerDegree) {
  return *mapMean(flipMap(a, b, ppd));
}

// The colour error of two uniform images by hand from the paper's equations: Hunt-adjusted
// CIELAB (a, b scaled by L / 100), HyAB, ^0.7, then the piecewise map with p_c = 0.4, p_t = 0.95
// and the green-blue maximum. CIELAB (D65) of sRGB green and blue are the textbook values.
double uniformColourError(double deltaL, double deltaHuntA, double deltaHuntB) {
  const double greenL = 87.7347, greenA = -86.1827, greenB = 83.1793;
  const double blueL = 32.3026, blueA = 79.1967, blueB = -107.8637;
  const double maxHyab = std::abs(greenL - blueL) + std::hypot(greenL / 100 * greenA - blueL / 100 * blueA,
                                                               greenL / 100 * greenB - blueL / 100 * blueB);
  const double emax = std::pow(maxHyab, 0.7);
  const double e = std::pow(std::abs(deltaL) + std::hypot(deltaHuntA, deltaHuntB), 0.7);
  return e < 0.4 * emax ? 0.95 * e / (0.4 * emax) : 0.95 + 0.05 * (e - 0.4 * emax) / (0.6 * emax);
}

TEST(Flip, IdenticalImagesHaveNoError) {
  const DisplayImage a = patternImage(37, 29);
  const ScalarMap map = flipMap(a, a);
  EXPECT_EQ(map.border, 0u);
  for (float value : map.values) EXPECT_EQ(value, 0.0f);
}

// The paper's normalisation: green against blue is the largest colour difference, error 1.
TEST(Flip, GreenAgainstBlueIsTheMaximumError) {
  const ScalarMap map = flipMap(constantImage(24, 24, 0, 1, 0), constantImage(24, 24, 0, 0, 1));
  for (float value : map.values) EXPECT_NEAR(value, 1.0f, 1e-4f);
}

TEST(Flip, UniformBlackAgainstWhiteMatchesTheEquationsByHand) {
  // L* 0 against 100, no chroma; uniform images have no features, so FLIP is the colour error.
  const double expected = uniformColourError(100.0, 0.0, 0.0);
  EXPECT_NEAR(expected, 0.967, 0.001);
  const ScalarMap map = flipMap(constantImage(24, 24, 0, 0, 0), constantImage(24, 24, 1, 1, 1));
  for (float value : map.values) EXPECT_NEAR(value, expected, 1e-3);
}

TEST(Flip, UniformRedAgainstBlackMatchesTheEquationsByHand) {
  // sRGB red is CIELAB (53.2408, 80.0925, 67.2032); the Hunt adjustment scales a, b by L / 100.
  const double lightness = 53.2408;
  const double expected = uniformColourError(lightness, lightness / 100 * 80.0925, lightness / 100 * 67.2032);
  const ScalarMap map = flipMap(constantImage(24, 24, 1, 0, 0), constantImage(24, 24, 0, 0, 0));
  for (float value : map.values) EXPECT_NEAR(value, expected, 1e-3);
}

TEST(Flip, UniformGreyStepMatchesTheEquationsByHand) {
  // Display grey 0.5 -> linear 0.21404 -> L* 53.389; display 0.6 -> linear 0.31855 -> L* 63.222.
  const double expected = uniformColourError(63.2223 - 53.3890, 0.0, 0.0);
  const ScalarMap map = flipMap(constantImage(24, 24, 0.5f, 0.5f, 0.5f), constantImage(24, 24, 0.6f, 0.6f, 0.6f));
  for (float value : map.values) EXPECT_NEAR(value, expected, 2e-3);
}

TEST(Flip, AWhitePixelOnBlackIsNearTheMaximum) {
  // A lone pixel is blurred by the CSF, but it is a point feature the other image lacks, which
  // drives the error towards 1 there.
  const DisplayImage black = constantImage(21, 21, 0, 0, 0);
  DisplayImage dot = black;
  const size_t centre = (10 * 21 + 10) * 3;
  dot.rgb[centre] = dot.rgb[centre + 1] = dot.rgb[centre + 2] = 1.0f;
  const ScalarMap map = flipMap(black, dot);
  EXPECT_GT(map.values[10 * 21 + 10], 0.8f);
  EXPECT_LT(map.values[0], map.values[10 * 21 + 10]);
}

TEST(Flip, GrowsWithTheDifference) {
  const DisplayImage a = patternImage(40, 30);
  double previous = 0.0;
  for (float shift : {0.01f, 0.03f, 0.1f, 0.3f}) {
    DisplayImage b = a;
    for (float& value : b.rgb) value = std::min(value + shift, 1.0f);
    const double flip = meanFlip(a, b);
    EXPECT_GT(flip, previous) << shift;
    previous = flip;
  }
  double previousNoise = 0.0;
  for (float sigma : {0.01f, 0.05f, 0.2f}) {
    const double flip = meanFlip(a, withNoise(a, sigma, 9));
    EXPECT_GT(flip, previousNoise) << sigma;
    previousNoise = flip;
  }
}

TEST(Flip, IsSymmetric) {
  const DisplayImage a = patternImage(33, 27);
  const DisplayImage b = withNoise(a, 0.1f, 10);
  EXPECT_NEAR(meanFlip(a, b), meanFlip(b, a), 1e-5);
}

TEST(Flip, StaysInTheUnitRange) {
  const ScalarMap map = flipMap(randomImage(31, 19, 11), randomImage(31, 19, 12));
  for (float value : map.values) {
    EXPECT_GE(value, 0.0f);
    EXPECT_LE(value, 1.0f);
  }
}

TEST(Flip, FineDetailMattersLessFromFurtherAway) {
  // A one-pixel checkerboard against flat grey: at more pixels per degree the CSF averages
  // the checkerboard away.
  DisplayImage checker = constantImage(32, 32, 0, 0, 0);
  for (uint32_t y = 0; y < 32; ++y)
    for (uint32_t x = 0; x < 32; ++x)
      if ((x + y) % 2) for (int c = 0; c < 3; ++c) checker.rgb[(size_t(y) * 32 + x) * 3 + size_t(c)] = 1.0f;
  const DisplayImage grey = constantImage(32, 32, 0.73536f, 0.73536f, 0.73536f);  // linear 0.5
  EXPECT_LT(meanFlip(checker, grey, 120.0f), meanFlip(checker, grey, 20.0f));
}

TEST(Flip, TinyImagesWork) {
  for (auto [w, h] : {std::pair{1u, 1u}, std::pair{2u, 3u}, std::pair{5u, 1u}}) {
    const ScalarMap map = flipMap(randomImage(w, h, 13), randomImage(w, h, 14));
    ASSERT_EQ(map.values.size(), size_t(w) * h);
    for (float value : map.values) EXPECT_TRUE(std::isfinite(value));
  }
}

TEST(Flip, BadArgumentsThrow) {
  testing::expectError([] { flipMap(randomImage(4, 4, 1), randomImage(4, 5, 1)); }, "4x4 vs 4x5");
  testing::expectError([] { flipMap(randomImage(4, 4, 1), randomImage(4, 4, 1), 0.0f); }, "pixels per degree");
  testing::expectError([] { flipMap(randomImage(4, 4, 1), randomImage(4, 4, 1), std::nanf("")); },
                       "pixels per degree");
}

}  // namespace
}  // namespace hmb::metrics
