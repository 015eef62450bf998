// LDR-FLIP, written from the equations of
//   P. Andersson, J. Nilsson, T. Akenine-Moller, M. Oskarsson, K. Astrom, M. D. Fairchild,
//   "FLIP: A Difference Evaluator for Alternating Images", Proc. ACM Comput. Graph. Interact.
//   Tech. 3(2), Article 15, 2020 (HPG 2020). https://doi.org/10.1145/3406183
//
// Colour pipeline: sRGB display values -> linear RGB -> XYZ -> YyCxCz (the opponent space that
// is linear in XYZ, so filtering there is meaningful); each channel is convolved with the
// spatial form of its contrast sensitivity function, a sum of Gaussians
//   s(r) = a1 sqrt(pi / b1) exp(-pi^2 r^2 / b1) + a2 sqrt(pi / b2) exp(-pi^2 r^2 / b2),
// r in degrees of visual angle, normalised to sum 1. The filtered image goes back to linear
// RGB, is clamped to [0, 1] and converted to CIELAB; a* and b* are scaled by 0.01 L* (the Hunt
// effect: chroma is less visible in dark colours); the colour difference is HyAB,
// |dL| + ||(da, db)||, raised to q_c = 0.7 and mapped piecewise-linearly onto [0, 1] so that the
// largest difference, green against blue, is 1 and p_c = 0.4 of it lands at p_t = 0.95.
//
// Feature pipeline: on the unfiltered luminance Y / Yn = (Yy + 16) / 116, edges are the
// gradient magnitude under the first derivative of a Gaussian and points the magnitude of the
// second derivatives, sigma = 0.5 w ppd with w = 0.082 degrees; each derivative kernel's positive
// weights sum to 1 and its negative weights to -1. The feature difference is
//   dE_f = (max(|edge_r - edge_t|, |point_r - point_t|) / sqrt(2))^q_f, q_f = 0.5,
// and the FLIP error is dE_c^(1 - dE_f): a feature that appears or vanishes pushes a colour
// error towards 1.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "hmblur/error.h"
#include "hmblur/image.h"
#include "runtime/metrics/metrics.h"
#include "runtime/metrics/separable_filter.h"

namespace hmb::metrics {

namespace {

using Vec3 = std::array<double, 3>;

// CSF parameters (a1, b1, a2, b2) of the paper's Table 1 for the achromatic, red-green and
// blue-yellow channels.
struct CsfParameters {
  double a1, b1, a2, b2;
};
constexpr std::array<CsfParameters, 3> kCsf = {{
    {1.0, 0.0047, 0.0, 1e-5},
    {1.0, 0.0053, 0.0, 1e-5},
    {34.1, 0.04, 13.5, 0.025},
}};
constexpr double kLargestB = 0.04;  // sets the filter radius shared by all three channels

constexpr double kColourExponent = 0.7;     // q_c
constexpr double kColourCutoff = 0.4;       // p_c
constexpr double kColourCutoffTarget = 0.95;  // p_t
constexpr double kFeatureExponent = 0.5;    // q_f
constexpr double kFeatureWidthDegrees = 0.082;  // w

// sRGB primaries, D65 white (IEC 61966-2-1).
constexpr double kRgbToXyz[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                                    {0.2126729, 0.7151522, 0.0721750},
                                    {0.0193339, 0.1191920, 0.9503041}};
constexpr double kXyzToRgb[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                    {-0.9692660, 1.8760108, 0.0415560},
                                    {0.0556434, -0.2040259, 1.0572252}};

Vec3 multiply(const double (&m)[3][3], const Vec3& v) {
  return {m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2], m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2],
          m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2]};
}

// The white the opponent and CIELAB spaces are relative to: XYZ of linear RGB (1, 1, 1).
const Vec3 kWhite = multiply(kRgbToXyz, {1.0, 1.0, 1.0});

Vec3 xyzToYyCxCz(const Vec3& xyz) {
  const double x = xyz[0] / kWhite[0], y = xyz[1] / kWhite[1], z = xyz[2] / kWhite[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}

Vec3 yyCxCzToXyz(const Vec3& opponent) {
  const double y = (opponent[0] + 16.0) / 116.0;
  const double x = y + opponent[1] / 500.0;
  const double z = y - opponent[2] / 200.0;
  return {x * kWhite[0], y * kWhite[1], z * kWhite[2]};
}

double labF(double t) {
  constexpr double delta = 6.0 / 29.0;
  return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0;
}

// Linear RGB in [0, 1] -> CIELAB with the Hunt adjustment of a* and b*.
Vec3 huntLab(const Vec3& linearRgb) {
  const Vec3 xyz = multiply(kRgbToXyz, linearRgb);
  const double fx = labF(xyz[0] / kWhite[0]), fy = labF(xyz[1] / kWhite[1]), fz = labF(xyz[2] / kWhite[2]);
  const double lightness = 116.0 * fy - 16.0;
  return {lightness, 0.01 * lightness * 500.0 * (fx - fy), 0.01 * lightness * 200.0 * (fy - fz)};
}

double hyab(const Vec3& a, const Vec3& b) {
  return std::abs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

// The CSF of one channel as up to two separable Gaussians, weights already normalised so the
// whole 2D kernel sums to 1.
struct CsfFilter {
  std::vector<float> profiles[2];  // exp(-pi^2 x^2 / (b ppd^2)), unnormalised
  double weights[2] = {0.0, 0.0};  // a sqrt(pi / b) / (2D sum), 0 for an absent term
};

CsfFilter csfFilter(const CsfParameters& csf, double pixelsPerDegree, int radius) {
  CsfFilter filter;
  const double amplitudes[2] = {csf.a1, csf.a2};
  const double widths[2] = {csf.b1, csf.b2};
  double total = 0.0;
  for (int term = 0; term < 2; ++term) {
    if (amplitudes[term] == 0.0) continue;
    std::vector<float>& profile = filter.profiles[term];
    double profileSum = 0.0;
    for (int x = -radius; x <= radius; ++x) {
      const double degrees = x / pixelsPerDegree;
      const double value = std::exp(-std::numbers::pi * std::numbers::pi * degrees * degrees / widths[term]);
      profile.push_back(float(value));
      profileSum += value;
    }
    filter.weights[term] = amplitudes[term] * std::sqrt(std::numbers::pi / widths[term]);
    total += filter.weights[term] * profileSum * profileSum;  // the 2D kernel is the outer product
  }
  for (double& weight : filter.weights) weight /= total;
  return filter;
}

Plane applyCsf(const Plane& channel, const CsfFilter& filter) {
  Plane result{.width = channel.width, .height = channel.height};
  result.values.assign(channel.values.size(), 0.0f);
  for (int term = 0; term < 2; ++term) {
    if (filter.weights[term] == 0.0) continue;
    const Plane blurred = convolveSeparable(channel, filter.profiles[term], filter.profiles[term]);
    for (size_t i = 0; i < result.values.size(); ++i)
      result.values[i] += float(filter.weights[term] * blurred.values[i]);
  }
  return result;
}

// The three YyCxCz planes of a display image.
std::array<Plane, 3> opponentPlanes(const DisplayImage& image) {
  std::array<Plane, 3> planes;
  for (Plane& plane : planes) {
    plane.width = image.width;
    plane.height = image.height;
    plane.values.resize(image.pixelCount());
  }
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    const Vec3 linear = {io::srgbToLinear(image.rgb[i * 3]), io::srgbToLinear(image.rgb[i * 3 + 1]),
                         io::srgbToLinear(image.rgb[i * 3 + 2])};
    const Vec3 opponent = xyzToYyCxCz(multiply(kRgbToXyz, linear));
    for (size_t c = 0; c < 3; ++c) planes[c].values[i] = float(opponent[c]);
  }
  return planes;
}

// Hunt-adjusted CIELAB of each pixel after the CSF filters.
std::vector<Vec3> filteredLab(const std::array<Plane, 3>& opponent, const std::array<CsfFilter, 3>& filters) {
  std::array<Plane, 3> filtered;
  for (size_t c = 0; c < 3; ++c) filtered[c] = applyCsf(opponent[c], filters[c]);
  std::vector<Vec3> lab(opponent[0].values.size());
  for (size_t i = 0; i < lab.size(); ++i) {
    Vec3 rgb = multiply(kXyzToRgb, yyCxCzToXyz({filtered[0].values[i], filtered[1].values[i], filtered[2].values[i]}));
    for (double& value : rgb) value = std::clamp(value, 0.0, 1.0);
    lab[i] = huntLab(rgb);
  }
  return lab;
}

// A derivative-of-Gaussian kernel scaled so its positive weights sum to 1 and its negative
// weights to -1.
std::vector<float> balancedDerivative(const std::vector<double>& raw) {
  double positive = 0.0, negative = 0.0;
  for (double w : raw) (w > 0.0 ? positive : negative) += w;
  std::vector<float> kernel(raw.size());
  for (size_t i = 0; i < raw.size(); ++i)
    kernel[i] = float(raw[i] > 0.0 ? raw[i] / positive : (raw[i] < 0.0 ? raw[i] / -negative : 0.0));
  return kernel;
}

struct FeatureKernels {
  std::vector<float> gaussian, first, second;
};

FeatureKernels featureKernels(double pixelsPerDegree) {
  const double sigma = 0.5 * kFeatureWidthDegrees * pixelsPerDegree;
  const int radius = int(std::ceil(3.0 * sigma));
  std::vector<double> first, second;
  for (int x = -radius; x <= radius; ++x) {
    const double g = std::exp(-double(x) * x / (2.0 * sigma * sigma));
    first.push_back(-x / (sigma * sigma) * g);
    second.push_back((double(x) * x / (sigma * sigma) - 1.0) / (sigma * sigma) * g);
  }
  return {gaussianKernel(float(sigma), radius), balancedDerivative(first), balancedDerivative(second)};
}

struct Features {
  std::vector<float> edges, points;
};

Features features(const Plane& yy, const FeatureKernels& kernels) {
  Plane luminance{.width = yy.width, .height = yy.height};
  luminance.values.resize(yy.values.size());
  for (size_t i = 0; i < yy.values.size(); ++i) luminance.values[i] = (yy.values[i] + 16.0f) / 116.0f;
  const Plane dx = convolveSeparable(luminance, kernels.first, kernels.gaussian);
  const Plane dy = convolveSeparable(luminance, kernels.gaussian, kernels.first);
  const Plane dxx = convolveSeparable(luminance, kernels.second, kernels.gaussian);
  const Plane dyy = convolveSeparable(luminance, kernels.gaussian, kernels.second);
  Features result;
  result.edges.resize(yy.values.size());
  result.points.resize(yy.values.size());
  for (size_t i = 0; i < yy.values.size(); ++i) {
    result.edges[i] = std::hypot(dx.values[i], dy.values[i]);
    result.points[i] = std::hypot(dxx.values[i], dyy.values[i]);
  }
  return result;
}

}  // namespace

ScalarMap flipMap(const DisplayImage& reference, const DisplayImage& test, float pixelsPerDegree) {
  requireSameSize(reference, test, "FLIP");
  if (!(pixelsPerDegree > 0.0f) || !std::isfinite(pixelsPerDegree))
    throw Error("FLIP: pixels per degree must be a positive number");

  const double ppd = pixelsPerDegree;
  const int csfRadius = int(std::ceil(3.0 * std::sqrt(kLargestB / (2.0 * std::numbers::pi * std::numbers::pi)) * ppd));
  const std::array<CsfFilter, 3> filters = {csfFilter(kCsf[0], ppd, csfRadius), csfFilter(kCsf[1], ppd, csfRadius),
                                            csfFilter(kCsf[2], ppd, csfRadius)};
  const FeatureKernels kernels = featureKernels(ppd);

  const std::array<Plane, 3> referenceOpponent = opponentPlanes(reference);
  const std::array<Plane, 3> testOpponent = opponentPlanes(test);
  const std::vector<Vec3> referenceLab = filteredLab(referenceOpponent, filters);
  const std::vector<Vec3> testLab = filteredLab(testOpponent, filters);
  const Features referenceFeatures = features(referenceOpponent[0], kernels);
  const Features testFeatures = features(testOpponent[0], kernels);

  const double largestDifference = std::pow(hyab(huntLab({0.0, 1.0, 0.0}), huntLab({0.0, 0.0, 1.0})), kColourExponent);
  const double cutoff = kColourCutoff * largestDifference;

  ScalarMap map{.width = reference.width, .height = reference.height, .border = 0};
  map.values.resize(reference.pixelCount());
  for (size_t i = 0; i < map.values.size(); ++i) {
    const double compressed = std::pow(hyab(referenceLab[i], testLab[i]), kColourExponent);
    const double colour =
        compressed < cutoff
            ? kColourCutoffTarget * compressed / cutoff
            : kColourCutoffTarget + (1.0 - kColourCutoffTarget) * (compressed - cutoff) / (largestDifference - cutoff);
    const double featureDifference =
        std::max(std::abs(referenceFeatures.edges[i] - testFeatures.edges[i]),
                 std::abs(referenceFeatures.points[i] - testFeatures.points[i])) /
        std::numbers::sqrt2;
    const double feature = std::pow(std::min(featureDifference, 1.0), kFeatureExponent);
    map.values[i] = float(std::clamp(std::pow(std::min(colour, 1.0), 1.0 - feature), 0.0, 1.0));
  }
  return map;
}

}  // namespace hmb::metrics
