// Where a method's error against the reference comes from: each blur-region pixel put in one
// class by what moves there, and each class's share of the region's squared error. The classes,
// first match wins:
// - curved path: a path near the pixel bends off the straight line that screen-space blur
//   assumes (rotation, dolly, perspective) by more than bendPixels at mid-shutter;
// - inner blur, traced: the pixel's own surface moves and the hybrid traced it (its ray mask:
//   what error is left there is the revealed background's, wrong surface or gathered wrongly;
//   or its shutter rays: their few shutter times);
// - inner blur, not traced: the pixel's own surface moves and no ray revealed what is behind it
//   (partial occlusion left to the gather: every pixel of a method that traces nothing);
// - outer blur: the pixel's surface stands still and a moving one near it sweeps over it;
// - other: nothing near the pixel moves by movingPixels (shading, noise, a deformation not followed).
// "Near" is within the longest path in the image (at most maxReachPixels), as a square window.
// The reference's own noise, when known (two independent halves of it), is summed per class:
// the part of each class's error no method could remove at that reference's sample count.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "hmblur/image.h"
#include "runtime/metrics/display_image.h"
#include "runtime/metrics/metrics.h"

namespace hmb::metrics {

enum class ErrorSource : uint8_t { Outside, CurvedPath, InnerTraced, InnerNotTraced, OuterBlur, Other };
inline constexpr std::array<ErrorSource, 5> kErrorSources = {ErrorSource::CurvedPath, ErrorSource::InnerTraced,
                                                              ErrorSource::InnerNotTraced, ErrorSource::OuterBlur,
                                                              ErrorSource::Other};
// "curved-path", "inner-traced", "inner-not-traced", "outer-blur", "other", "outside".
const char* errorSourceName(ErrorSource source);
// Its colour in errorSourceImage (8-bit sRGB).
std::array<uint8_t, 3> errorSourceColor(ErrorSource source);

struct ErrorSourceSettings {
  float movingPixels = 0.5f;  // a path this long over the shutter moves
  float bendPixels = 0.5f;    // a mid-shutter point this far off the straight line curves
  uint32_t maxReachPixels = 64;
};

struct ErrorSourceInputs {
  const DisplayImage* reference = nullptr;
  const DisplayImage* test = nullptr;
  const BlurRegion* region = nullptr;
  std::span<const float> pathLength;  // per pixel, pixels (runtime/metrics/screen_paths.h)
  std::span<const float> pathBend;    // per pixel, pixels
  std::span<const uint32_t> rayMask;  // the hybrid's, non-zero where traced; empty: nothing traced
  // Per pixel, the expected squared error (mean over R, G, B) of the reference's own noise;
  // empty when unknown. referenceNoise() makes it from two independent halves.
  std::span<const float> referenceNoise;
};

struct ErrorSourceRow {
  ErrorSource source = ErrorSource::Other;
  size_t pixels = 0;
  double squaredError = 0.0;  // summed over its pixels (mean over R, G, B per pixel)
  double share = 0.0;         // of the region's squared error; 0 when the region has none
  std::optional<double> noise;  // the reference's noise summed over its pixels
};

struct ErrorSources {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t reachPixels = 0;  // the window "near" meant
  std::vector<ErrorSource> perPixel;
  std::vector<ErrorSourceRow> rows;  // in kErrorSources' order, empty classes included
  size_t regionPixels = 0;
  double squaredError = 0.0;     // over the region
  std::optional<double> noise;   // likewise
};

// Throws hmb::Error when the inputs' sizes differ.
ErrorSources explainErrorSources(const ErrorSourceInputs& inputs, const ErrorSourceSettings& settings = {});

// The expected squared error of the mean of two independent renders a and b of the same
// reference, per pixel (mean over R, G, B of (a - b)^2 / 4): the noise of the reference made
// of both.
std::vector<float> referenceNoise(const DisplayImage& a, const DisplayImage& b);

// The classes in their colours over the reference in dim grey (outside the region).
io::Rgba8Image errorSourceImage(const ErrorSources& sources, const DisplayImage& reference);

// {"reach_pixels", "region_pixels", "squared_error", "noise", "classes": [{"class", "pixels",
// "squared_error", "share", "noise"}]}
nlohmann::json errorSourcesJson(const ErrorSources& sources);

}  // namespace hmb::metrics
