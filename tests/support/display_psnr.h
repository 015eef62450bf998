// PSNR of two display images (RGBA8) over R, G and B, peak 255: how far one device's or one
// profile's image lies from another's, without the metrics library.
#pragma once

#include <cmath>
#include <cstddef>

#include "hmblur/image.h"

namespace hmb::test {

// +infinity where the images are equal; the images must have one size.
inline double displayPsnr(const io::Rgba8Image& a, const io::Rgba8Image& b) {
  double sum = 0.0;
  size_t values = 0;
  for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double d = double(a.pixels[i]) - double(b.pixels[i]);
    sum += d * d;
    ++values;
  }
  return sum == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 * double(values) / sum);
}

}  // namespace hmb::test
