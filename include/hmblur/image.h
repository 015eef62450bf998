// Images on the host: a layered float image (beauty + AOVs, what an EXR holds) and 8-bit RGBA
// (what a PNG holds), and the display transform between them. Reading and writing the files is
// image_files.h, in a library of its own (hmb_io): the renderer needs none of it.
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

// The display transform, on the CPU: the plain C++ reference of the encode_display kernel.
// Linear value -> NaN/Inf to 0 -> clamp [0, 1] -> sRGB transfer function -> round to 8 bits.
// Alpha is clamped and quantized without the transfer function.
float linearToSrgb(float linear);
// Its inverse, the sRGB EOTF, exact (in double): encoded value in [0, 1] -> linear.
double srgbToLinear(double encoded);
uint8_t encodeSrgb8(float linear);
Rgba8Image encodeDisplay(uint32_t width, uint32_t height, std::span<const glm::vec4> linearRgba);

}  // namespace hmb::io
