// Separable 2D convolution of single-channel float images; the filters of SSIM and FLIP.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace hmb::metrics {

// One channel, width * height floats, top row first.
struct Plane {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> values;
};

// Convolves with `rowKernel` along x, then `columnKernel` along y. Kernels have odd length and
// are centred; coordinates outside the image are clamped to the edge (the border pixel repeats).
// Sums are taken in double so that long kernels lose no precision.
Plane convolveSeparable(const Plane& image, std::span<const float> rowKernel, std::span<const float> columnKernel);

// exp(-x^2 / (2 sigma^2)) for x in [-radius, radius], normalised to sum 1.
std::vector<float> gaussianKernel(float sigma, int radius);

}  // namespace hmb::metrics
