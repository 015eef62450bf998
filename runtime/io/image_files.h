// Image files on the host: EXR (through OpenEXR) and PNG (through stb). The library hmb_io,
// which the command line, the benchmarks, the metrics and the tests link; the renderer does not.
#pragma once

#include <filesystem>

#include "hmblur/image.h"

namespace hmb::io {

// EXR: every layer's channels are written as "<layer>.<channel>" ("R" for the beauty layer),
// FLOAT or UINT, ZIP-compressed. Non-finite floats are written as 0. Throws hmb::Error.
void writeExr(const std::filesystem::path& path, const LayeredImage& image);
LayeredImage readExr(const std::filesystem::path& path);

// PNG through stb. Throws hmb::Error.
void writePng(const std::filesystem::path& path, const Rgba8Image& image);
Rgba8Image readPng(const std::filesystem::path& path);

}  // namespace hmb::io
