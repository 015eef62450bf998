// CPU reference of the encode_display kernel. Kept in plain float arithmetic, step for step
// the same as the kernel, so the two can be compared code for code.
#include <cmath>
#include <string>

#include "hmblur/error.h"
#include "hmblur/image.h"

namespace hmb::io {

namespace {

// NaN/Inf to 0, then clamp to [0, 1]: no non-finite value may reach the 8-bit output.
float sanitizeUnit(float value) {
  if (!std::isfinite(value)) return 0.0f;
  return std::fmin(std::fmax(value, 0.0f), 1.0f);
}

uint8_t quantizeUnit(float unit) { return static_cast<uint8_t>(std::floor(unit * 255.0f + 0.5f)); }

}  // namespace

// The sRGB OETF (IEC 61966-2-1), exact: linear segment below 0.0031308, power segment above.
float linearToSrgb(float linear) {
  if (linear < 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

double srgbToLinear(double encoded) {
  return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

uint8_t encodeSrgb8(float linear) { return quantizeUnit(linearToSrgb(sanitizeUnit(linear))); }

Rgba8Image encodeDisplay(uint32_t width, uint32_t height, std::span<const glm::vec4> linearRgba) {
  const size_t pixelCount = size_t(width) * height;
  if (linearRgba.size() != pixelCount) {
    throw Error("encodeDisplay: " + std::to_string(linearRgba.size()) + " pixels given for a " +
                std::to_string(width) + "x" + std::to_string(height) + " image");
  }
  Rgba8Image image;
  image.width = width;
  image.height = height;
  image.pixels.resize(pixelCount * 4);
  for (size_t i = 0; i < pixelCount; ++i) {
    const glm::vec4& pixel = linearRgba[i];
    image.pixels[i * 4 + 0] = encodeSrgb8(pixel.r);
    image.pixels[i * 4 + 1] = encodeSrgb8(pixel.g);
    image.pixels[i * 4 + 2] = encodeSrgb8(pixel.b);
    image.pixels[i * 4 + 3] = quantizeUnit(sanitizeUnit(pixel.a));  // alpha is linear coverage
  }
  return image;
}

}  // namespace hmb::io
