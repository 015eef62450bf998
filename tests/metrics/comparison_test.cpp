#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "runtime/metrics/metrics.h"
#include "tests/metrics/metrics_test_images.h"

namespace hmb::metrics {
namespace {

using testing::constantImage;
using testing::expectError;
using testing::patternImage;
using testing::randomImage;

void setPixel(DisplayImage& image, uint32_t x, uint32_t y, float r, float g, float b) {
  float* pixel = image.rgb.data() + (size_t(y) * image.width + x) * 3;
  pixel[0] = r;
  pixel[1] = g;
  pixel[2] = b;
}

TEST(BlurRegion, HoldsThePixelsThatDifferByMoreThanTheThreshold) {
  const DisplayImage sharp = constantImage(4, 1, 0.5f, 0.5f, 0.5f);
  DisplayImage reference = sharp;
  setPixel(reference, 0, 0, 0.5f + 1.0f / 255.0f, 0.5f, 0.5f);  // one 8-bit code: rounding, not blur
  setPixel(reference, 1, 0, 0.5f, 0.5f + 2.0f / 255.0f, 0.5f);  // two codes in one channel: blur
  setPixel(reference, 2, 0, 0.5f, 0.5f, 0.1f);
  const BlurRegion region = blurRegion(reference, sharp);
  EXPECT_EQ(region.inside, (std::vector<uint8_t>{0, 1, 1, 0}));
  EXPECT_EQ(region.pixelCount, 2u);
  EXPECT_EQ(blurRegion(reference, sharp, 0.0f).pixelCount, 3u);
}

TEST(Comparison, RegionValuesMeasureOnlyTheRegion) {
  // 20x20 frame; the test image is wrong only inside a 6x6 square, which is also the region.
  const DisplayImage sharp = patternImage(20, 20);
  DisplayImage reference = sharp;
  DisplayImage test = sharp;
  for (uint32_t y = 7; y < 13; ++y)
    for (uint32_t x = 7; x < 13; ++x) {
      setPixel(reference, x, y, 0.9f, 0.1f, 0.1f);
      setPixel(test, x, y, 0.7f, 0.1f, 0.1f);
    }
  const BlurRegion region = blurRegion(reference, sharp);
  ASSERT_EQ(region.pixelCount, 36u);
  const Comparison comparison = compareImages(reference, test, &region);
  ASSERT_TRUE(comparison.region.has_value());
  EXPECT_EQ(comparison.region->pixels, 36u);
  EXPECT_NEAR(comparison.region->mse, 0.04 / 3.0, 1e-6);
  EXPECT_NEAR(comparison.frame.mse, 0.04 / 3.0 * 36.0 / 400.0, 1e-7);
  EXPECT_NEAR(comparison.region->psnr, 10.0 * std::log10(3.0 / 0.04), 1e-3);
  EXPECT_LT(comparison.region->psnr, comparison.frame.psnr);
  EXPECT_GT(comparison.region->flip, comparison.frame.flip);
  ASSERT_TRUE(comparison.region->ssim && comparison.frame.ssim);
  EXPECT_LT(*comparison.region->ssim, *comparison.frame.ssim);
}

TEST(Comparison, AnEmptyRegionHasNoValues) {
  const DisplayImage sharp = patternImage(16, 16);
  const BlurRegion region = blurRegion(sharp, sharp);
  EXPECT_EQ(region.pixelCount, 0u);
  const Comparison comparison = compareImages(sharp, testing::withNoise(sharp, 0.1f, 1), &region);
  EXPECT_TRUE(comparison.regionGiven);
  EXPECT_FALSE(comparison.region.has_value());
  const nlohmann::json json = metricsJson(comparison);
  EXPECT_TRUE(json["region"].is_null());
  EXPECT_EQ(json["region_pixels"], 0);
  EXPECT_TRUE(json["frame"]["psnr_db"].is_number());

  const Comparison noRegion = compareImages(sharp, sharp);
  EXPECT_FALSE(noRegion.regionGiven);
  EXPECT_TRUE(metricsJson(noRegion)["region_pixels"].is_null());
}

TEST(Comparison, RegionInTheBorderOnlyHasNoSsimButTheOtherValues) {
  const DisplayImage sharp = constantImage(20, 20, 0.2f, 0.2f, 0.2f);
  DisplayImage reference = sharp;
  setPixel(reference, 0, 0, 1.0f, 1.0f, 1.0f);
  const BlurRegion region = blurRegion(reference, sharp);
  const Comparison comparison = compareImages(reference, sharp, &region);
  ASSERT_TRUE(comparison.region.has_value());
  EXPECT_FALSE(comparison.region->ssim.has_value());
  EXPECT_GT(comparison.region->flip, 0.0);
  EXPECT_TRUE(metricsJson(comparison)["region"]["ssim"].is_null());
}

TEST(Comparison, IdenticalImagesWriteNullPsnrBesideZeroMse) {
  const DisplayImage a = patternImage(16, 12);
  const Comparison comparison = compareImages(a, a);
  EXPECT_EQ(comparison.frame.psnr, std::numeric_limits<double>::infinity());
  const nlohmann::json json = metricsJson(comparison);
  EXPECT_TRUE(json["frame"]["psnr_db"].is_null());
  EXPECT_EQ(json["frame"]["mse"], 0.0);
  EXPECT_NEAR(json["frame"]["ssim"].get<double>(), 1.0, 1e-6);
  EXPECT_EQ(json["frame"]["flip"], 0.0);
  EXPECT_EQ(json["width"], 16);
  // The JSON must round-trip: no NaN or infinity anywhere.
  EXPECT_EQ(nlohmann::json::parse(json.dump()), json);
}

TEST(Comparison, NonFiniteInputsNeverGiveNan) {
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> rgba(12 * 12 * 4, 0.5f);
  rgba[0] = std::nanf("");
  rgba[5] = inf;
  rgba[10] = -inf;
  rgba[200] = 1e30f;
  const DisplayImage fromLinear = displayImageFromLinearRgba(12, 12, rgba);
  DisplayImage handFilled = constantImage(12, 12, 0.5f, 0.5f, 0.5f);
  handFilled.rgb[3] = std::nanf("");
  handFilled.rgb[7] = inf;
  handFilled.rgb[40] = -2.0f;
  for (const DisplayImage* test : {&fromLinear, static_cast<const DisplayImage*>(&handFilled)}) {
    const BlurRegion region = blurRegion(*test, constantImage(12, 12, 0.5f, 0.5f, 0.5f));
    const Comparison comparison = compareImages(constantImage(12, 12, 0.5f, 0.5f, 0.5f), *test, &region);
    EXPECT_FALSE(std::isnan(comparison.frame.psnr));
    ASSERT_TRUE(comparison.frame.ssim.has_value());
    EXPECT_TRUE(std::isfinite(*comparison.frame.ssim));
    EXPECT_TRUE(std::isfinite(comparison.frame.flip));
    for (float value : comparison.flip.values) EXPECT_TRUE(std::isfinite(value));
    for (float value : comparison.ssim.values) EXPECT_TRUE(std::isfinite(value));
    ASSERT_TRUE(comparison.region.has_value());
    EXPECT_TRUE(std::isfinite(comparison.region->flip));
  }
}

TEST(Comparison, MismatchedSizesAreOneLineErrors) {
  const DisplayImage a = randomImage(8, 6, 1);
  const DisplayImage b = randomImage(6, 8, 2);
  expectError([&] { compareImages(a, b); }, "image sizes differ (8x6 vs 6x8)");
  expectError([&] { blurRegion(a, b); }, "8x6 vs 6x8");
  expectError([&] { meanSquaredError(a, b); }, "8x6 vs 6x8");
  const BlurRegion region = blurRegion(b, b);
  expectError([&] { compareImages(a, a, &region); }, "does not fit");
  DisplayImage broken = a;
  broken.rgb.pop_back();
  expectError([&] { compareImages(a, broken); }, "instead of");
}

TEST(ErrorImage, HasTheMapSizeAndRunsFromDarkToBright) {
  ScalarMap map{.width = 3, .height = 2, .values = {0.0f, 0.25f, 0.5f, 0.75f, 1.0f, std::nanf("")}};
  const io::Rgba8Image image = errorImage(map);
  EXPECT_EQ(image.width, 3u);
  EXPECT_EQ(image.height, 2u);
  ASSERT_EQ(image.pixels.size(), 3u * 2u * 4u);
  auto brightness = [&](size_t i) { return int(image.pixels[i * 4]) + image.pixels[i * 4 + 1] + image.pixels[i * 4 + 2]; };
  for (size_t i = 0; i < 6; ++i) EXPECT_EQ(image.pixels[i * 4 + 3], 255);
  for (size_t i = 1; i < 5; ++i) EXPECT_GT(brightness(i), brightness(i - 1)) << i;
  EXPECT_EQ(brightness(5), brightness(0));  // NaN shows as no error
  EXPECT_EQ(std::vector<uint8_t>(image.pixels.begin(), image.pixels.begin() + 3), (std::vector<uint8_t>{0, 0, 4}));
  EXPECT_EQ(std::vector<uint8_t>(image.pixels.begin() + 16, image.pixels.begin() + 19),
            (std::vector<uint8_t>{252, 253, 191}));
}

TEST(MetricsJson, SettingsNameTheDefinitions) {
  const nlohmann::json settings = metricsSettingsJson();
  EXPECT_EQ(settings["flip"]["pixels_per_degree"], 67.0);
  EXPECT_EQ(settings["ssim"]["k1"], 0.01);
  EXPECT_NEAR(settings["blur_region"]["threshold"].get<double>(), 1.5 / 255.0, 1e-7);
}

}  // namespace
}  // namespace hmb::metrics
