#include "runtime/metrics/display_image.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "hmblur/error.h"
#include "runtime/io/image_files.h"

namespace hmb::metrics {

namespace {

// The display value the PNG of this pixel holds: quantized to 8 bits, so that a PNG and an EXR
// of the same render score the same (FLIP's power laws turn the quantization steps alone into
// a mean error of about 0.01 where one image is quantized and the other not).
float displayValue(float linear) { return float(io::encodeSrgb8(linear)) / 255.0f; }

std::string lowerExtension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

}  // namespace

std::string sizeText(uint32_t width, uint32_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

void requireSameSize(const DisplayImage& reference, const DisplayImage& test, const std::string& what) {
  if (reference.width != test.width || reference.height != test.height)
    throw Error(what + ": image sizes differ (" + sizeText(reference.width, reference.height) + " vs " +
                sizeText(test.width, test.height) + ")");
}

DisplayImage displayImageFromRgba8(const io::Rgba8Image& image) {
  DisplayImage display{.width = image.width, .height = image.height};
  const size_t pixelCount = display.pixelCount();
  if (image.pixels.size() != pixelCount * 4)
    throw Error("8-bit image of " + sizeText(image.width, image.height) + " holds " +
                std::to_string(image.pixels.size()) + " bytes instead of " + std::to_string(pixelCount * 4));
  display.rgb.resize(pixelCount * 3);
  for (size_t i = 0; i < pixelCount; ++i)
    for (size_t c = 0; c < 3; ++c) display.rgb[i * 3 + c] = float(image.pixels[i * 4 + c]) / 255.0f;
  return display;
}

DisplayImage displayImageFromLinearRgba(uint32_t width, uint32_t height, std::span<const float> linearRgba) {
  DisplayImage display{.width = width, .height = height};
  const size_t pixelCount = display.pixelCount();
  if (linearRgba.size() != pixelCount * 4)
    throw Error("linear RGBA image of " + sizeText(width, height) + " holds " + std::to_string(linearRgba.size()) +
                " floats instead of " + std::to_string(pixelCount * 4));
  display.rgb.resize(pixelCount * 3);
  for (size_t i = 0; i < pixelCount; ++i)
    for (size_t c = 0; c < 3; ++c) display.rgb[i * 3 + c] = displayValue(linearRgba[i * 4 + c]);
  return display;
}

DisplayImage displayImageFromLayered(const io::LayeredImage& image) {
  const io::ImageLayer* beauty = image.find("");
  if (!beauty || beauty->isUint) throw Error("the image has no beauty layer (channels R, G, B)");
  const size_t channelCount = beauty->channels.size();
  size_t channelIndex[3];
  const char* names[3] = {"R", "G", "B"};
  for (size_t c = 0; c < 3; ++c) {
    const auto it = std::find(beauty->channels.begin(), beauty->channels.end(), names[c]);
    if (it == beauty->channels.end()) throw Error(std::string("the beauty layer has no channel ") + names[c]);
    channelIndex[c] = size_t(it - beauty->channels.begin());
  }
  DisplayImage display{.width = image.width, .height = image.height};
  const size_t pixelCount = display.pixelCount();
  if (beauty->values.size() != pixelCount * channelCount)
    throw Error("the beauty layer holds " + std::to_string(beauty->values.size()) + " values for a " +
                sizeText(image.width, image.height) + " image");
  display.rgb.resize(pixelCount * 3);
  for (size_t i = 0; i < pixelCount; ++i)
    for (size_t c = 0; c < 3; ++c) display.rgb[i * 3 + c] = displayValue(beauty->values[i * channelCount + channelIndex[c]]);
  return display;
}

DisplayImage loadDisplayImage(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  if (ext == ".png") return displayImageFromRgba8(io::readPng(path));
  if (ext == ".exr") {
    const io::LayeredImage image = io::readExr(path);
    try {
      return displayImageFromLayered(image);
    } catch (const Error& e) {
      throw Error("cannot read EXR '" + path.string() + "': " + e.what());
    }
  }
  throw Error("cannot read '" + path.string() + "': not a .png or .exr file");
}

}  // namespace hmb::metrics
