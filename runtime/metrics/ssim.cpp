// SSIM after Wang, Bovik, Sheikh, Simoncelli, "Image Quality Assessment: From Error Visibility
// to Structural Similarity", IEEE TIP 13(4), 2004: local means, variances and covariance under
// an 11x11 Gaussian window (sigma 1.5, weights summing to 1), then
//   SSIM = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2))
// with C1 = (K1 L)^2, C2 = (K2 L)^2. The Gaussian is separable, so each local moment is two 1D
// passes.
#include <cmath>

#include "runtime/metrics/metrics.h"
#include "runtime/metrics/separable_filter.h"

namespace hmb::metrics {

namespace {

constexpr float kSigma = 1.5f;
constexpr double kK1 = 0.01;
constexpr double kK2 = 0.03;
constexpr double kDynamicRange = 1.0;

Plane channelPlane(const DisplayImage& image, size_t channel) {
  Plane plane{.width = image.width, .height = image.height};
  plane.values.resize(image.pixelCount());
  for (size_t i = 0; i < plane.values.size(); ++i) plane.values[i] = image.rgb[i * 3 + channel];
  return plane;
}

Plane product(const Plane& a, const Plane& b) {
  Plane result{.width = a.width, .height = a.height};
  result.values.resize(a.values.size());
  for (size_t i = 0; i < a.values.size(); ++i) result.values[i] = a.values[i] * b.values[i];
  return result;
}

}  // namespace

ScalarMap ssimMap(const DisplayImage& reference, const DisplayImage& test) {
  requireSameSize(reference, test, "SSIM");
  const std::vector<float> window = gaussianKernel(kSigma, int(kSsimWindowRadius));
  const double c1 = (kK1 * kDynamicRange) * (kK1 * kDynamicRange);
  const double c2 = (kK2 * kDynamicRange) * (kK2 * kDynamicRange);

  ScalarMap map{.width = reference.width, .height = reference.height, .border = kSsimWindowRadius};
  map.values.assign(reference.pixelCount(), 0.0f);
  for (size_t channel = 0; channel < 3; ++channel) {
    const Plane x = channelPlane(reference, channel);
    const Plane y = channelPlane(test, channel);
    const Plane muX = convolveSeparable(x, window, window);
    const Plane muY = convolveSeparable(y, window, window);
    const Plane meanXX = convolveSeparable(product(x, x), window, window);
    const Plane meanYY = convolveSeparable(product(y, y), window, window);
    const Plane meanXY = convolveSeparable(product(x, y), window, window);
    for (size_t i = 0; i < map.values.size(); ++i) {
      const double mx = muX.values[i];
      const double my = muY.values[i];
      const double varX = double(meanXX.values[i]) - mx * mx;
      const double varY = double(meanYY.values[i]) - my * my;
      const double covXY = double(meanXY.values[i]) - mx * my;
      const double ssim = ((2.0 * mx * my + c1) * (2.0 * covXY + c2)) /
                          ((mx * mx + my * my + c1) * (varX + varY + c2));
      map.values[i] += float(ssim / 3.0);
    }
  }
  return map;
}

}  // namespace hmb::metrics
