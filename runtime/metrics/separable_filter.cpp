#include "runtime/metrics/separable_filter.h"

#include <algorithm>
#include <cmath>

namespace hmb::metrics {

Plane convolveSeparable(const Plane& image, std::span<const float> rowKernel, std::span<const float> columnKernel) {
  const int width = int(image.width);
  const int height = int(image.height);
  const int rowRadius = int(rowKernel.size() / 2);
  const int columnRadius = int(columnKernel.size() / 2);

  Plane rows{.width = image.width, .height = image.height};
  rows.values.resize(image.values.size());
  for (int y = 0; y < height; ++y) {
    const float* source = image.values.data() + size_t(y) * width;
    float* target = rows.values.data() + size_t(y) * width;
    for (int x = 0; x < width; ++x) {
      double sum = 0.0;
      for (int k = -rowRadius; k <= rowRadius; ++k)
        sum += double(rowKernel[size_t(k + rowRadius)]) * source[std::clamp(x + k, 0, width - 1)];
      target[x] = float(sum);
    }
  }

  Plane result{.width = image.width, .height = image.height};
  result.values.resize(image.values.size());
  std::vector<double> sums(static_cast<size_t>(width));
  for (int y = 0; y < height; ++y) {
    // Row by row, so that the inner loop walks memory in order.
    std::fill(sums.begin(), sums.end(), 0.0);
    for (int k = -columnRadius; k <= columnRadius; ++k) {
      const double weight = columnKernel[size_t(k + columnRadius)];
      const float* source = rows.values.data() + size_t(std::clamp(y + k, 0, height - 1)) * width;
      for (int x = 0; x < width; ++x) sums[size_t(x)] += weight * source[x];
    }
    float* target = result.values.data() + size_t(y) * width;
    for (int x = 0; x < width; ++x) target[x] = float(sums[size_t(x)]);
  }
  return result;
}

std::vector<float> gaussianKernel(float sigma, int radius) {
  std::vector<double> weights(size_t(2 * radius + 1));
  double sum = 0.0;
  for (int x = -radius; x <= radius; ++x) {
    weights[size_t(x + radius)] = std::exp(-double(x) * x / (2.0 * double(sigma) * sigma));
    sum += weights[size_t(x + radius)];
  }
  std::vector<float> kernel(weights.size());
  for (size_t i = 0; i < weights.size(); ++i) kernel[i] = float(weights[i] / sum);
  return kernel;
}

}  // namespace hmb::metrics
