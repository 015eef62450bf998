// Error metrics between a reference and a test image, on display values (see display_image.h):
// PSNR, SSIM and FLIP, over the whole frame and over the blur region.
//
// Definitions, chosen once for every report:
// - PSNR: peak 1, MSE over the R, G, B values of the pixels measured. Identical images have an
//   infinite PSNR: `psnr` is +infinity, and JSON writes null beside "mse": 0 (JSON has no
//   infinity, and a large sentinel would be averaged as if it were a measurement).
// - SSIM: Wang, Bovik, Sheikh, Simoncelli 2004, "Image Quality Assessment: From Error
//   Visibility to Structural Similarity", with their constants: 11x11 Gaussian window, sigma
//   1.5, K1 = 0.01, K2 = 0.03, L = 1. Computed on each of R, G, B and averaged, because a blur
//   error can move colour without moving luma (a red object smeared over a green wall), which
//   SSIM on luma would not see. Only windows that lie wholly inside the image count ("valid",
//   as in the authors' own code): the map's outer 5 pixels are excluded from every mean, and an
//   image under 11x11 has no SSIM.
// - FLIP: LDR-FLIP (Andersson et al. 2020) at 67 pixels per degree unless told otherwise; see
//   flip.cpp. The map holds one value in [0, 1] per pixel; the metric is its mean.
// - Blur region: the pixels where any R, G, B display value of the reference and of the sharp
//   frame differ by more than 1.5/255, i.e. by two 8-bit codes or more. One code is left out
//   because two renderers rounding the same colour can differ by one code where nothing moved;
//   a blur trail that changes no value by two codes is invisible. Region values are the
//   PSNR of the MSE over region pixels and the means of the SSIM and FLIP maps there; with no
//   region pixel they are absent.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "hmblur/image.h"
#include "runtime/metrics/display_image.h"

namespace hmb::metrics {

inline constexpr float kDefaultPixelsPerDegree = 67.0f;  // 0.7 m from a 0.7 m wide 3840-pixel monitor
inline constexpr float kBlurRegionThreshold = 1.5f / 255.0f;
inline constexpr uint32_t kSsimWindowRadius = 5;  // 11x11

struct MetricOptions {
  float pixelsPerDegree = kDefaultPixelsPerDegree;
  float blurRegionThreshold = kBlurRegionThreshold;
};

// One float per pixel. Pixels within `border` of the image edge have no full window behind
// their value (it is computed with clamped edges, fit to look at) and no mean counts them.
struct ScalarMap {
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t border = 0;
  std::vector<float> values;

  bool counts(uint32_t x, uint32_t y) const {
    return x >= border && y >= border && x + border < width && y + border < height;
  }
};

// Pixel mask: 1 inside the region.
struct BlurRegion {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> inside;
  size_t pixelCount = 0;  // pixels inside
};

BlurRegion blurRegion(const DisplayImage& reference, const DisplayImage& sharp,
                      float threshold = kBlurRegionThreshold);

// Mean over R, G, B of the squared difference, optionally over region pixels only (nullopt
// when the region is empty).
double meanSquaredError(const DisplayImage& reference, const DisplayImage& test);
std::optional<double> meanSquaredError(const DisplayImage& reference, const DisplayImage& test,
                                       const BlurRegion& region);
// 10 log10(1 / mse); +infinity for mse 0.
double psnrFromMse(double mse);

// Per-pixel SSIM, the mean of the R, G, B SSIM maps; border = 5.
ScalarMap ssimMap(const DisplayImage& reference, const DisplayImage& test);
// Per-pixel LDR-FLIP error in [0, 1]; border = 0.
ScalarMap flipMap(const DisplayImage& reference, const DisplayImage& test,
                  float pixelsPerDegree = kDefaultPixelsPerDegree);

// Mean over the pixels the map counts, and over those inside the region too; nullopt when no
// pixel qualifies.
std::optional<double> mapMean(const ScalarMap& map);
std::optional<double> mapMean(const ScalarMap& map, const BlurRegion& region);

struct MetricValues {
  size_t pixels = 0;            // pixels measured
  double mse = 0.0;
  double psnr = 0.0;            // dB; +infinity when mse is 0
  std::optional<double> ssim;   // absent when no full 11x11 window lies in the pixels measured
  double flip = 0.0;
};

struct Comparison {
  uint32_t width = 0;
  uint32_t height = 0;
  MetricValues frame;
  bool regionGiven = false;             // a sharp frame was given, so a region was measured
  size_t regionPixels = 0;
  std::optional<MetricValues> region;   // absent when not given or empty
  ScalarMap ssim;
  ScalarMap flip;
};

// Every metric of `test` against `reference`; over `region` too when one is given (from
// blurRegion(reference, sharp)). Throws hmb::Error on mismatched sizes.
Comparison compareImages(const DisplayImage& reference, const DisplayImage& test, const BlurRegion* region = nullptr,
                         const MetricOptions& options = {});

// {"frame": {"pixels", "mse", "psnr_db" (null when infinite), "ssim" (null when absent),
//  "flip"}, "region": the same or null}. Region is null when no sharp frame was given or the
//  region is empty; "region_pixels" says which.
nlohmann::json metricsJson(const Comparison& comparison);
// The definitions behind the numbers: display transform, SSIM and FLIP settings, threshold.
nlohmann::json metricsSettingsJson(const MetricOptions& options = {});

// A map in [0, 1] through the magma colour map (black-purple-orange-white), opaque; values
// outside [0, 1] are clamped.
io::Rgba8Image errorImage(const ScalarMap& map);

}  // namespace hmb::metrics
