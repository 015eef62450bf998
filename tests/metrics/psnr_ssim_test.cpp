#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "runtime/metrics/metrics.h"
#include "tests/metrics/metrics_test_images.h"

namespace hmb::metrics {
namespace {

using testing::constantImage;
using testing::patternImage;
using testing::randomImage;
using testing::withNoise;

TEST(Psnr, OfAKnownMse) {
  // Every value off by 0.1: MSE 0.01, PSNR 20 dB.
  const DisplayImage a = constantImage(7, 5, 0.5f, 0.2f, 0.9f);
  const DisplayImage b = constantImage(7, 5, 0.6f, 0.1f, 0.8f);
  EXPECT_NEAR(meanSquaredError(a, b), 0.01, 1e-7);
  EXPECT_NEAR(psnrFromMse(meanSquaredError(a, b)), 20.0, 1e-4);
  // One channel off by 0.3: MSE 0.09 / 3 = 0.03.
  const DisplayImage c = constantImage(7, 5, 0.5f, 0.5f, 0.5f);
  const DisplayImage d = constantImage(7, 5, 0.5f, 0.8f, 0.5f);
  EXPECT_NEAR(meanSquaredError(c, d), 0.03, 1e-7);
  EXPECT_NEAR(psnrFromMse(0.03), 10.0 * std::log10(1.0 / 0.03), 1e-9);
  EXPECT_DOUBLE_EQ(psnrFromMse(1.0), 0.0);
}

TEST(Psnr, IdenticalImagesAreInfinite) {
  const DisplayImage a = randomImage(9, 4, 1);
  EXPECT_EQ(meanSquaredError(a, a), 0.0);
  EXPECT_EQ(psnrFromMse(0.0), std::numeric_limits<double>::infinity());
}

// SSIM straight from the formula of Wang et al. 2004: the 11x11 Gaussian window evaluated as a
// 2D sum for one pixel, no separable filtering, in double.
double directSsim(const DisplayImage& a, const DisplayImage& b, int cx, int cy, int channel) {
  double weights[11][11];
  double total = 0.0;
  for (int dy = -5; dy <= 5; ++dy)
    for (int dx = -5; dx <= 5; ++dx) total += weights[dy + 5][dx + 5] = std::exp(-(dx * dx + dy * dy) / (2 * 1.5 * 1.5));
  double muA = 0, muB = 0;
  auto at = [&](const DisplayImage& image, int x, int y) {
    return double(image.rgb[(size_t(y) * image.width + size_t(x)) * 3 + size_t(channel)]);
  };
  for (int dy = -5; dy <= 5; ++dy)
    for (int dx = -5; dx <= 5; ++dx) {
      const double w = weights[dy + 5][dx + 5] / total;
      muA += w * at(a, cx + dx, cy + dy);
      muB += w * at(b, cx + dx, cy + dy);
    }
  double varA = 0, varB = 0, cov = 0;
  for (int dy = -5; dy <= 5; ++dy)
    for (int dx = -5; dx <= 5; ++dx) {
      const double w = weights[dy + 5][dx + 5] / total;
      const double da = at(a, cx + dx, cy + dy) - muA, db = at(b, cx + dx, cy + dy) - muB;
      varA += w * da * da;
      varB += w * db * db;
      cov += w * da * db;
    }
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  return (2 * muA * muB + c1) * (2 * cov + c2) / ((muA * muA + muB * muB + c1) * (varA + varB + c2));
}

TEST(Ssim, IdenticalImagesScoreOne) {
  const DisplayImage a = randomImage(23, 17, 2);
  const ScalarMap map = ssimMap(a, a);
  EXPECT_EQ(map.border, 5u);
  for (float value : map.values) EXPECT_NEAR(value, 1.0f, 1e-5f);
  EXPECT_NEAR(*mapMean(map), 1.0, 1e-6);
}

TEST(Ssim, MatchesTheDirectGaussianWindowFormula) {
  const DisplayImage a = randomImage(14, 13, 3);
  const DisplayImage b = withNoise(a, 0.1f, 4);
  const ScalarMap map = ssimMap(a, b);
  double sum = 0.0;
  int count = 0;
  for (int y = 5; y + 5 < 13; ++y)
    for (int x = 5; x + 5 < 14; ++x) {
      const double expected = (directSsim(a, b, x, y, 0) + directSsim(a, b, x, y, 1) + directSsim(a, b, x, y, 2)) / 3;
      EXPECT_NEAR(map.values[size_t(y) * 14 + size_t(x)], expected, 1e-5) << x << "," << y;
      sum += expected;
      ++count;
    }
  ASSERT_EQ(count, 4 * 3);  // only the windows that fit
  EXPECT_NEAR(*mapMean(map), sum / count, 1e-5);
}

TEST(Ssim, IsSymmetric) {
  const DisplayImage a = patternImage(30, 20);
  const DisplayImage b = withNoise(a, 0.05f, 5);
  EXPECT_NEAR(*mapMean(ssimMap(a, b)), *mapMean(ssimMap(b, a)), 1e-6);
}

TEST(Ssim, FallsAsAConstantShiftGrows) {
  const DisplayImage a = patternImage(40, 30);
  double previous = 1.0;
  for (float shift : {0.02f, 0.05f, 0.1f, 0.2f}) {
    DisplayImage b = a;
    for (float& value : b.rgb) value = std::min(value + shift, 1.0f);
    const double ssim = *mapMean(ssimMap(a, b));
    EXPECT_LT(ssim, previous) << shift;
    previous = ssim;
  }
}

TEST(Ssim, FallsAsNoiseGrows) {
  const DisplayImage a = patternImage(40, 30);
  double previous = 1.0;
  for (float sigma : {0.01f, 0.03f, 0.1f, 0.3f}) {
    const double ssim = *mapMean(ssimMap(a, withNoise(a, sigma, 6)));
    EXPECT_LT(ssim, previous) << sigma;
    previous = ssim;
  }
  EXPECT_LT(previous, 0.5);
}

TEST(Ssim, SeesAColourChangeThatKeepsLuma) {
  // Red and green of about equal luma: SSIM on luma would call them the same image.
  const DisplayImage red = constantImage(16, 16, 0.9f, 0.0f, 0.0f);
  const DisplayImage green = constantImage(16, 16, 0.0f, 0.6f, 0.0f);
  EXPECT_LT(*mapMean(ssimMap(red, green)), 0.5);
}

TEST(Ssim, ImagesUnderTheWindowHaveNoSsim) {
  const DisplayImage a = randomImage(10, 30, 7);
  const ScalarMap map = ssimMap(a, withNoise(a, 0.1f, 8));
  EXPECT_FALSE(mapMean(map).has_value());
  for (float value : map.values) EXPECT_TRUE(std::isfinite(value));
}

TEST(Ssim, MismatchedSizesThrow) {
  testing::expectError([] { ssimMap(randomImage(12, 12, 1), randomImage(13, 12, 1)); }, "12x12 vs 13x12");
}

}  // namespace
}  // namespace hmb::metrics
