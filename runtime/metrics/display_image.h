// The image every metric works on: display values (linear -> NaN/Inf to 0 -> clamp [0, 1] ->
// sRGB -> 8 bits, the display transform of the PNGs), three floats per pixel. Made from floats
// it is quantized as the PNG of the same image is, so both score the same.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "hmblur/image.h"

namespace hmb::metrics {

struct DisplayImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgb;  // sRGB-encoded display values in [0, 1], R G B per pixel, top row first

  size_t pixelCount() const { return size_t(width) * height; }
};

// 8-bit display pixels: value / 255; alpha is ignored.
DisplayImage displayImageFromRgba8(const io::Rgba8Image& image);

// Linear RGBA floats, 4 per pixel: NaN/Inf -> 0, clamp [0, 1], sRGB transfer function, 8 bits.
DisplayImage displayImageFromLinearRgba(uint32_t width, uint32_t height, std::span<const float> linearRgba);

// The beauty layer (channels R, G, B) of a layered float image, through the display transform.
DisplayImage displayImageFromLayered(const io::LayeredImage& image);

// A .png (display values as stored) or .exr (beauty layer R, G, B, linear) file. Throws
// hmb::Error with a one-line message naming the file.
DisplayImage loadDisplayImage(const std::filesystem::path& path);

// "64x32"
std::string sizeText(uint32_t width, uint32_t height);

// Throws hmb::Error unless both images have the same size; `what` names them in the message.
void requireSameSize(const DisplayImage& reference, const DisplayImage& test, const std::string& what);

}  // namespace hmb::metrics
