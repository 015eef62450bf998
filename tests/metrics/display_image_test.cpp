#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "runtime/io/image_files.h"
#include "runtime/metrics/display_image.h"
#include "tests/metrics/metrics_test_images.h"

namespace hmb::metrics {
namespace {

using testing::expectError;
using testing::scratchPath;

TEST(DisplayImage, FromRgba8DividesBy255AndDropsAlpha) {
  const io::Rgba8Image image{.width = 2, .height = 1, .pixels = {0, 51, 255, 7, 128, 1, 2, 0}};
  const DisplayImage display = displayImageFromRgba8(image);
  EXPECT_EQ(display.width, 2u);
  EXPECT_EQ(display.height, 1u);
  const std::vector<float> expected = {0.0f, 0.2f, 1.0f, 128.0f / 255.0f, 1.0f / 255.0f, 2.0f / 255.0f};
  ASSERT_EQ(display.rgb.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_FLOAT_EQ(display.rgb[i], expected[i]) << i;
}

// Made from floats, the display values are the 8-bit codes the PNG of the same image holds.
TEST(DisplayImage, FromLinearAppliesTheDisplayTransformQuantizedAsAPng) {
  const std::vector<float> rgba = {0.5f, 0.001f, 0.2f, 1.0f};
  const DisplayImage display = displayImageFromLinearRgba(1, 1, rgba);
  for (size_t c = 0; c < 3; ++c) {
    EXPECT_FLOAT_EQ(display.rgb[c], float(io::encodeSrgb8(rgba[c])) / 255.0f) << c;
    EXPECT_NEAR(display.rgb[c], io::linearToSrgb(rgba[c]), 0.5f / 255.0f) << c;
  }
  const std::vector<glm::vec4> pixel = {glm::vec4(rgba[0], rgba[1], rgba[2], rgba[3])};
  const io::Rgba8Image png = io::encodeDisplay(1, 1, pixel);
  EXPECT_EQ(display.rgb, displayImageFromRgba8(png).rgb);
}

TEST(DisplayImage, NonFiniteAndOutOfRangeLinearValuesAreSanitized) {
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<float> rgba = {std::nanf(""), inf, -inf, 1.0f, 2.0f, -0.5f, 1.0f, 1.0f};
  const DisplayImage display = displayImageFromLinearRgba(2, 1, rgba);
  const std::vector<float> expected = {0.0f, 0.0f, 0.0f, 1.0f, 0.0f, 1.0f};  // NaN and Inf show as black
  ASSERT_EQ(display.rgb.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_FLOAT_EQ(display.rgb[i], expected[i]) << i;
}

TEST(DisplayImage, WrongBufferSizesThrow) {
  expectError([] { displayImageFromLinearRgba(2, 2, std::vector<float>(12)); }, "2x2");
  expectError([] { displayImageFromRgba8(io::Rgba8Image{.width = 3, .height = 1, .pixels = {1, 2, 3}}); }, "3x1");
}

TEST(DisplayImage, FromLayeredFindsTheBeautyChannelsByName) {
  io::LayeredImage image{.width = 1, .height = 1};
  image.layers.push_back({.name = "depth", .channels = {"Z"}, .values = {5.0f}});
  image.layers.push_back({.name = "", .channels = {"A", "B", "G", "R"}, .values = {1.0f, 0.0f, 1.0f, 0.5f}});
  const DisplayImage display = displayImageFromLayered(image);
  EXPECT_FLOAT_EQ(display.rgb[0], float(io::encodeSrgb8(0.5f)) / 255.0f);
  EXPECT_FLOAT_EQ(display.rgb[1], 1.0f);
  EXPECT_FLOAT_EQ(display.rgb[2], 0.0f);
}

TEST(DisplayImage, LoadsPngAndExr) {
  const auto png = scratchPath(".png");
  io::writePng(png, io::Rgba8Image{.width = 2, .height = 1, .pixels = {255, 0, 0, 255, 0, 0, 51, 255}});
  const DisplayImage fromPng = loadDisplayImage(png);
  EXPECT_EQ(fromPng.rgb, (std::vector<float>{1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.2f}));

  const auto exr = scratchPath(".exr");
  io::LayeredImage layered{.width = 1, .height = 2};
  layered.layers.push_back({.name = "", .channels = {"R", "G", "B", "A"}, .values = {0.25f, 0, 0, 1, 0, 1, 4, 1}});
  io::writeExr(exr, layered);
  const DisplayImage fromExr = loadDisplayImage(exr);
  ASSERT_EQ(fromExr.height, 2u);
  EXPECT_FLOAT_EQ(fromExr.rgb[0], float(io::encodeSrgb8(0.25f)) / 255.0f);
  EXPECT_FLOAT_EQ(fromExr.rgb[5], 1.0f);
}

TEST(DisplayImage, LoadErrorsAreOneLineAndNameTheFile) {
  const auto missing = scratchPath(".png");
  expectError([&] { loadDisplayImage(missing); }, "no such file");
  expectError([&] { loadDisplayImage(scratchPath(".exr")); }, "no such file");
  expectError([&] { loadDisplayImage(scratchPath(".bmp")); }, "not a .png or .exr");

  const auto aovOnly = scratchPath(".exr");
  io::LayeredImage layered{.width = 1, .height = 1};
  layered.layers.push_back({.name = "depth", .channels = {"Z"}, .values = {1.0f}});
  io::writeExr(aovOnly, layered);
  expectError([&] { loadDisplayImage(aovOnly); }, aovOnly.string());
  expectError([&] { loadDisplayImage(aovOnly); }, "beauty");

  const auto noBlue = scratchPath("_rg.exr");
  io::LayeredImage rg{.width = 1, .height = 1};
  rg.layers.push_back({.name = "", .channels = {"R", "G"}, .values = {1.0f, 1.0f}});
  io::writeExr(noBlue, rg);
  expectError([&] { loadDisplayImage(noBlue); }, "no channel B");
}

}  // namespace
}  // namespace hmb::metrics
