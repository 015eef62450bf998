#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "hmblur/error.h"
#include "hmblur/image.h"

namespace hmb::io {
namespace {

// The sRGB EOTF, the inverse of linearToSrgb, in double so the test does not share the
// implementation's rounding.
double srgbToLinear(double encoded) {
  if (encoded <= 0.04045) return encoded / 12.92;
  return std::pow((encoded + 0.055) / 1.055, 2.4);
}

TEST(DisplayTransform, KnownValues) {
  EXPECT_EQ(encodeSrgb8(0.0f), 0);
  EXPECT_EQ(encodeSrgb8(1.0f), 255);
  EXPECT_EQ(encodeSrgb8(0.5f), 188);
  EXPECT_EQ(encodeSrgb8(0.18f), 118);  // middle grey
  EXPECT_EQ(encodeSrgb8(0.001f), 3);   // linear segment: 12.92 * 0.001 * 255 = 3.29
  EXPECT_NEAR(linearToSrgb(0.5f), 0.735357, 1e-6);
  EXPECT_FLOAT_EQ(linearToSrgb(0.0f), 0.0f);
  EXPECT_NEAR(linearToSrgb(1.0f), 1.0, 1e-6);
}

TEST(DisplayTransform, SegmentBoundaryIsContinuous) {
  constexpr float kBoundary = 0.0031308f;
  const float below = std::nextafter(kBoundary, 0.0f);
  EXPECT_FLOAT_EQ(linearToSrgb(below), 12.92f * below);  // still on the linear segment
  EXPECT_NEAR(linearToSrgb(kBoundary), 0.04045, 1e-6);   // first value of the power segment
  EXPECT_NEAR(linearToSrgb(below), linearToSrgb(kBoundary), 1e-6);
  EXPECT_EQ(encodeSrgb8(below), 10);
  EXPECT_EQ(encodeSrgb8(kBoundary), 10);  // 0.04045 * 255 = 10.31
}

TEST(DisplayTransform, OutOfRangeAndNonFiniteInputs) {
  constexpr float kInf = std::numeric_limits<float>::infinity();
  EXPECT_EQ(encodeSrgb8(-0.0f), 0);
  EXPECT_EQ(encodeSrgb8(-1e-8f), 0);
  EXPECT_EQ(encodeSrgb8(-5.0f), 0);
  EXPECT_EQ(encodeSrgb8(1.0001f), 255);
  EXPECT_EQ(encodeSrgb8(1e30f), 255);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::max()), 255);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(encodeSrgb8(-std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(encodeSrgb8(kInf), 0);
  EXPECT_EQ(encodeSrgb8(-kInf), 0);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::denorm_min()), 0);
}

TEST(DisplayTransform, MonotonicOverAFineSweepAndReachesEveryCode) {
  std::vector<bool> reached(256, false);
  float previousEncoded = linearToSrgb(0.0f);
  int previousCode = encodeSrgb8(-0.1f);
  constexpr int kSteps = 1'200'000;
  for (int i = 0; i <= kSteps; ++i) {
    const float linear = -0.1f + 1.2f * float(i) / float(kSteps);
    const int code = encodeSrgb8(linear);
    ASSERT_GE(code, previousCode) << "at " << linear;
    previousCode = code;
    reached[size_t(code)] = true;
    if (linear >= 0.0f && linear <= 1.0f) {
      const float encoded = linearToSrgb(linear);
      ASSERT_GE(encoded, previousEncoded) << "at " << linear;
      previousEncoded = encoded;
    }
  }
  for (int code = 0; code < 256; ++code) EXPECT_TRUE(reached[size_t(code)]) << code;
}

TEST(DisplayTransform, DecodingTheCodeLandsWithinHalfAStep) {
  // Round to nearest: the input lies between the decoded midpoints to the neighbouring codes.
  constexpr int kSteps = 100'000;
  constexpr double kTolerance = 1e-6;  // float pow versus the double reference
  for (int i = 0; i <= kSteps; ++i) {
    const float linear = float(i) / float(kSteps);
    const int code = encodeSrgb8(linear);
    const double lower = srgbToLinear(std::max(0.0, (code - 0.5) / 255.0));
    const double upper = srgbToLinear(std::min(1.0, (code + 0.5) / 255.0));
    ASSERT_GE(double(linear), lower - kTolerance) << "code " << code;
    ASSERT_LE(double(linear), upper + kTolerance) << "code " << code;
    ASSERT_NEAR(double(linearToSrgb(linear)), code / 255.0, 0.5 / 255.0 + kTolerance);
  }
}

TEST(DisplayTransform, EncodeDisplayAppliesTheTransferToRgbButNotAlpha) {
  const std::vector<glm::vec4> pixels = {
      {0.0f, 0.5f, 1.0f, 0.5f},
      {2.0f, -1.0f, std::numeric_limits<float>::quiet_NaN(), 1.5f},
      {0.18f, 0.18f, 0.18f, std::numeric_limits<float>::infinity()},
      {0.25f, 0.75f, 0.001f, -0.5f},
      {1.0f, 1.0f, 1.0f, 0.2f},
      {0.0f, 0.0f, 0.0f, 0.0f},
  };
  const Rgba8Image image = encodeDisplay(3, 2, pixels);
  EXPECT_EQ(image.width, 3u);
  EXPECT_EQ(image.height, 2u);
  // clang-format off
  const std::vector<uint8_t> expected = {
      0,   188, 255, 128,  // alpha 0.5 -> 127.5 rounds up, linearly
      255, 0,   0,   255,  //
      118, 118, 118, 0,    // Inf alpha -> 0
      encodeSrgb8(0.25f), encodeSrgb8(0.75f), 3, 0,  //
      255, 255, 255, 51,   // 0.2 * 255 = 51
      0,   0,   0,   0,
  };
  // clang-format on
  EXPECT_EQ(image.pixels, expected);
}

TEST(DisplayTransform, EncodeDisplayRejectsASizeMismatch) {
  const std::vector<glm::vec4> pixels(5);
  EXPECT_THROW(encodeDisplay(3, 2, pixels), hmb::Error);
  EXPECT_NO_THROW(encodeDisplay(5, 1, pixels));
}

}  // namespace
}  // namespace hmb::io
