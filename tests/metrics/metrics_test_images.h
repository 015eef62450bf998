// Small display images for the metrics tests, and the check for one-line errors.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <random>
#include <string>

#include "hmblur/error.h"
#include "runtime/metrics/display_image.h"
#include "tests/support/expect_error.h"

namespace hmb::metrics::testing {

inline DisplayImage constantImage(uint32_t width, uint32_t height, float r, float g, float b) {
  DisplayImage image{.width = width, .height = height};
  for (size_t i = 0; i < image.pixelCount(); ++i) image.rgb.insert(image.rgb.end(), {r, g, b});
  return image;
}

inline DisplayImage randomImage(uint32_t width, uint32_t height, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  DisplayImage image{.width = width, .height = height};
  image.rgb.resize(image.pixelCount() * 3);
  for (float& value : image.rgb) value = unit(rng);
  return image;
}

// `image` plus Gaussian noise of the given standard deviation, clamped to [0, 1].
inline DisplayImage withNoise(const DisplayImage& image, float sigma, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> noise(0.0f, sigma);
  DisplayImage result = image;
  for (float& value : result.rgb) value = std::clamp(value + noise(rng), 0.0f, 1.0f);
  return result;
}

// A soft-edged pattern with structure at several scales, so SSIM and FLIP have edges to see.
inline DisplayImage patternImage(uint32_t width, uint32_t height) {
  DisplayImage image{.width = width, .height = height};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const float r = 0.5f + 0.4f * std::sin(0.3f * float(x)) * std::cos(0.2f * float(y));
      const float g = (x / 8 + y / 8) % 2 ? 0.8f : 0.2f;
      const float b = float(x + y) / float(width + height);
      image.rgb.insert(image.rgb.end(), {r, g, b});
    }
  return image;
}

inline std::filesystem::path scratchPath(const std::string& suffix) {
  const std::filesystem::path dir = std::filesystem::path(HMB_TEST_DATA_DIR) / "metrics";
  std::filesystem::create_directories(dir);
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path path = dir / (std::string(info->test_suite_name()) + "_" + info->name() + suffix);
  std::filesystem::remove(path);
  return path;
}

using hmb::test::expectError;

}  // namespace hmb::metrics::testing
