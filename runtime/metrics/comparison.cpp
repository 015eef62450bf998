#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "hmblur/error.h"
#include "runtime/metrics/metrics.h"

namespace hmb::metrics {

namespace {

void requireRegionSize(const DisplayImage& image, const BlurRegion& region) {
  if (image.width != region.width || image.height != region.height)
    throw Error("blur region of " + sizeText(region.width, region.height) + " does not fit an image of " +
                sizeText(image.width, image.height));
}

// Display values are in [0, 1] when made by display_image.h; a hand-filled image may not be,
// and no metric may turn a stray NaN into a NaN result.
DisplayImage sanitized(const DisplayImage& image) {
  DisplayImage copy = image;
  for (float& value : copy.rgb) value = std::isfinite(value) ? std::clamp(value, 0.0f, 1.0f) : 0.0f;
  return copy;
}

void requireConsistent(const DisplayImage& image, const char* what) {
  if (image.rgb.size() != image.pixelCount() * 3)
    throw Error(std::string(what) + " image of " + sizeText(image.width, image.height) + " holds " +
                std::to_string(image.rgb.size()) + " values instead of " + std::to_string(image.pixelCount() * 3));
}

double pixelSquaredError(const DisplayImage& a, const DisplayImage& b, size_t pixel) {
  double sum = 0.0;
  for (size_t c = 0; c < 3; ++c) {
    const double d = double(a.rgb[pixel * 3 + c]) - double(b.rgb[pixel * 3 + c]);
    sum += d * d;
  }
  return sum;
}

nlohmann::json valuesJson(const MetricValues& values) {
  return {{"pixels", values.pixels},
          {"mse", values.mse},
          {"psnr_db", std::isfinite(values.psnr) ? nlohmann::json(values.psnr) : nlohmann::json(nullptr)},
          {"ssim", values.ssim ? nlohmann::json(*values.ssim) : nlohmann::json(nullptr)},
          {"flip", values.flip}};
}

// Magma (the matplotlib colour map by Smith and van der Walt), eleven evenly spaced sRGB
// stops; linear interpolation between them is close enough for a picture of where errors are.
constexpr std::array<std::array<uint8_t, 3>, 11> kMagma = {{{0x00, 0x00, 0x04},
                                                           {0x14, 0x0e, 0x36},
                                                           {0x3b, 0x0f, 0x70},
                                                           {0x64, 0x1a, 0x80},
                                                           {0x8c, 0x29, 0x81},
                                                           {0xb7, 0x37, 0x79},
                                                           {0xde, 0x49, 0x68},
                                                           {0xf7, 0x70, 0x5c},
                                                           {0xfe, 0x9f, 0x6d},
                                                           {0xfe, 0xcf, 0x92},
                                                           {0xfc, 0xfd, 0xbf}}};

}  // namespace

BlurRegion blurRegion(const DisplayImage& reference, const DisplayImage& sharp, float threshold) {
  requireConsistent(reference, "reference");
  requireConsistent(sharp, "sharp");
  requireSameSize(reference, sharp, "blur region of the reference and the sharp frame");
  const DisplayImage a = sanitized(reference), b = sanitized(sharp);
  BlurRegion region{.width = reference.width, .height = reference.height};
  region.inside.resize(reference.pixelCount());
  for (size_t i = 0; i < region.inside.size(); ++i) {
    bool differs = false;
    for (size_t c = 0; c < 3; ++c) differs |= std::abs(a.rgb[i * 3 + c] - b.rgb[i * 3 + c]) > threshold;
    region.inside[i] = differs ? 1 : 0;
    region.pixelCount += differs ? 1 : 0;
  }
  return region;
}

double meanSquaredError(const DisplayImage& reference, const DisplayImage& test) {
  requireConsistent(reference, "reference");
  requireConsistent(test, "test");
  requireSameSize(reference, test, "MSE");
  const DisplayImage a = sanitized(reference), b = sanitized(test);
  double sum = 0.0;
  for (size_t i = 0; i < a.pixelCount(); ++i) sum += pixelSquaredError(a, b, i);
  return a.pixelCount() == 0 ? 0.0 : sum / (3.0 * double(a.pixelCount()));
}

std::optional<double> meanSquaredError(const DisplayImage& reference, const DisplayImage& test,
                                       const BlurRegion& region) {
  requireConsistent(reference, "reference");
  requireConsistent(test, "test");
  requireSameSize(reference, test, "MSE");
  requireRegionSize(reference, region);
  const DisplayImage a = sanitized(reference), b = sanitized(test);
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < a.pixelCount(); ++i) {
    if (!region.inside[i]) continue;
    sum += pixelSquaredError(a, b, i);
    ++count;
  }
  if (count == 0) return std::nullopt;
  return sum / (3.0 * double(count));
}

double psnrFromMse(double mse) {
  if (!(mse > 0.0)) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / mse);
}

std::optional<double> mapMean(const ScalarMap& map) {
  double sum = 0.0;
  size_t count = 0;
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x)
      if (map.counts(x, y)) {
        sum += map.values[size_t(y) * map.width + x];
        ++count;
      }
  if (count == 0) return std::nullopt;
  return sum / double(count);
}

std::optional<double> mapMean(const ScalarMap& map, const BlurRegion& region) {
  if (map.width != region.width || map.height != region.height)
    throw Error("blur region of " + sizeText(region.width, region.height) + " does not fit a map of " +
                sizeText(map.width, map.height));
  double sum = 0.0;
  size_t count = 0;
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      const size_t i = size_t(y) * map.width + x;
      if (region.inside[i] && map.counts(x, y)) {
        sum += map.values[i];
        ++count;
      }
    }
  if (count == 0) return std::nullopt;
  return sum / double(count);
}

Comparison compareImages(const DisplayImage& reference, const DisplayImage& test, const BlurRegion* region,
                         const MetricOptions& options) {
  requireConsistent(reference, "reference");
  requireConsistent(test, "test");
  requireSameSize(reference, test, "compare");
  if (reference.pixelCount() == 0) throw Error("compare: the images are empty");
  if (region) requireRegionSize(reference, *region);
  const DisplayImage a = sanitized(reference), b = sanitized(test);

  Comparison result{.width = a.width, .height = a.height};
  result.ssim = ssimMap(a, b);
  result.flip = flipMap(a, b, options.pixelsPerDegree);

  result.frame.pixels = a.pixelCount();
  result.frame.mse = meanSquaredError(a, b);
  result.frame.psnr = psnrFromMse(result.frame.mse);
  result.frame.ssim = mapMean(result.ssim);
  result.frame.flip = mapMean(result.flip).value_or(0.0);

  if (region) {
    result.regionGiven = true;
    result.regionPixels = region->pixelCount;
    if (const std::optional<double> mse = meanSquaredError(a, b, *region)) {
      MetricValues values;
      values.pixels = region->pixelCount;
      values.mse = *mse;
      values.psnr = psnrFromMse(*mse);
      values.ssim = mapMean(result.ssim, *region);
      values.flip = mapMean(result.flip, *region).value_or(0.0);
      result.region = values;
    }
  }
  return result;
}

nlohmann::json metricsJson(const Comparison& comparison) {
  nlohmann::json json = {{"width", comparison.width},
                         {"height", comparison.height},
                         {"frame", valuesJson(comparison.frame)},
                         {"region", comparison.region ? valuesJson(*comparison.region) : nlohmann::json(nullptr)}};
  json["region_pixels"] = comparison.regionGiven ? nlohmann::json(comparison.regionPixels) : nlohmann::json(nullptr);
  return json;
}

nlohmann::json metricsSettingsJson(const MetricOptions& options) {
  return {
      {"display_transform", "linear -> NaN/Inf to 0 -> clamp [0, 1] -> sRGB; PNG values as stored"},
      {"psnr", "peak 1, MSE over R, G, B; null when the images are identical (infinite PSNR)"},
      {"ssim",
       {{"reference", "Wang et al. 2004"},
        {"window", "11x11 Gaussian, sigma 1.5"},
        {"k1", 0.01},
        {"k2", 0.03},
        {"dynamic_range", 1.0},
        {"channels", "mean of R, G, B"},
        {"borders", "valid windows only"}}},
      {"flip", {{"reference", "Andersson et al. 2020, LDR-FLIP"}, {"pixels_per_degree", options.pixelsPerDegree}}},
      {"blur_region",
       {{"definition", "pixels where any R, G, B display value of reference and sharp differ by more than the threshold"},
        {"threshold", options.blurRegionThreshold}}},
  };
}

io::Rgba8Image errorImage(const ScalarMap& map) {
  io::Rgba8Image image{.width = map.width, .height = map.height};
  image.pixels.resize(size_t(map.width) * map.height * 4);
  for (size_t i = 0; i < map.values.size(); ++i) {
    const float value = std::isfinite(map.values[i]) ? std::clamp(map.values[i], 0.0f, 1.0f) : 0.0f;
    const float position = value * float(kMagma.size() - 1);
    const size_t lower = std::min(size_t(position), kMagma.size() - 2);
    const float t = position - float(lower);
    for (size_t c = 0; c < 3; ++c)
      image.pixels[i * 4 + c] =
          uint8_t(std::lround((1.0f - t) * kMagma[lower][c] + t * kMagma[lower + 1][c]));
    image.pixels[i * 4 + 3] = 255;
  }
  return image;
}

}  // namespace hmb::metrics
