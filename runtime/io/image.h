// Images on the host: a layered float image for EXR (beauty + AOVs) and 8-bit RGBA for PNG.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace hmb::io {

// One named layer of a layered image. The beauty layer has the empty name and channels
// R, G, B, A; AOVs are e.g. "depth" {Z}, "normal" {X, Y, Z}, "velocity" {X, Y}, "objectId" {id}.
struct ImageLayer {
  std::string name;
  std::vector<std::string> channels;
  bool isUint = false;           // object ids are stored as UINT channels, everything else FLOAT
  std::vector<float> values;     // interleaved, width * height * channels.size(), when !isUint
  std::vector<uint32_t> ids;     // interleaved, when isUint
};

struct LayeredImage {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<ImageLayer> layers;

  const ImageLayer* find(const std::string& name) const;
};

struct Rgba8Image {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> pixels;  // width * height * 4, top row first
};

// EXR: every layer's channels are written as "<layer>.<channel>" ("R" for the beauty layer),
// FLOAT or UINT, ZIP-compressed. Non-finite floats are written as 0. Throws hmb::Error.
void writeExr(const std::filesystem::path& path, const LayeredImage& image);
LayeredImage readExr(const std::filesystem::path& path);

// PNG through stb. Throws hmb::Error.
void writePng(const std::filesystem::path& path, const Rgba8Image& image);
Rgba8Image readPng(const std::filesystem::path& path);

// The display transform, on the CPU: the plain C++ reference of the encode_display kernel.
// Linear value -> NaN/Inf to 0 -> clamp [0, 1] -> sRGB transfer function -> round to 8 bits.
// Alpha is clamped and quantized without the transfer function.
float linearToSrgb(float linear);
// Its inverse, the sRGB EOTF, exact (in double): encoded value in [0, 1] -> linear.
double srgbToLinear(double encoded);
uint8_t encodeSrgb8(float linear);
Rgba8Image encodeDisplay(uint32_t width, uint32_t height, std::span<const glm::vec4> linearRgba);

}  // namespace hmb::io
