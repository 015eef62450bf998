// 8-bit RGBA PNG files through stb. stb is compiled here with internal linkage (STB_*_STATIC):
// this copy cannot collide with another stb in the program, and its global settings (such as
// vertical flip on load) cannot be changed by other code.
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#endif
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_NO_STDIO  // files are read here, so a missing file gets its own message
#include <stb/stb_image.h>
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBIW_ZLIB_COMPRESS hmbDeflate  // stb's own deflate packs pictures loosely; zlib's best level does not
static unsigned char* hmbDeflate(unsigned char* data, int length, int* outLength, int /*quality*/);
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <zlib.h>

#include "hmblur/error.h"
#include "runtime/io/image_files.h"

// stb frees what this returns with free(); a null return makes the write fail (and say so).
static unsigned char* hmbDeflate(unsigned char* data, int length, int* outLength, int /*quality*/) {
  uLongf size = compressBound(uLong(length));
  auto* out = static_cast<unsigned char*>(std::malloc(size));
  if (out == nullptr || compress2(out, &size, data, uLong(length), Z_BEST_COMPRESSION) != Z_OK) {
    std::free(out);
    return nullptr;
  }
  *outLength = int(size);
  return out;
}

namespace hmb::io {

namespace {

[[noreturn]] void fail(const char* action, const std::filesystem::path& path,
                       const std::string& reason) {
  throw Error(std::string(action) + " PNG '" + path.string() + "': " + reason);
}

constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P',  'N',  'G',
                                                        '\r', '\n', 0x1a, '\n'};

}  // namespace

void writePng(const std::filesystem::path& path, const Rgba8Image& image) {
  if (image.width == 0 || image.height == 0) {
    fail("cannot write", path,
         "image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
             " is empty");
  }
  // stb takes int sizes and an int row stride.
  constexpr uint32_t kMaxSide = uint32_t(std::numeric_limits<int>::max() / 4);
  if (image.width > kMaxSide || image.height > kMaxSide)
    fail("cannot write", path, "image too large");
  const size_t expected = size_t(image.width) * image.height * 4;
  if (image.pixels.size() != expected) {
    fail("cannot write", path,
         "holds " + std::to_string(image.pixels.size()) + " bytes, expected " +
             std::to_string(expected) + " (" + std::to_string(image.width) + "x" +
             std::to_string(image.height) + "x4)");
  }
  const int width = int(image.width);
  errno = 0;  // stb reports failure only as 0; errno from its fopen/fwrite says why
  if (stbi_write_png(path.string().c_str(), width, int(image.height), 4, image.pixels.data(),
                     width * 4) == 0) {
    fail("cannot write", path, errno != 0 ? std::strerror(errno) : "the file could not be written");
  }
}

Rgba8Image readPng(const std::filesystem::path& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) fail("cannot read", path, "no such file");
  if (!std::filesystem::is_regular_file(status)) fail("cannot read", path, "not a regular file");
  std::ifstream stream(path, std::ios::binary);
  if (!stream) fail("cannot read", path, "the file could not be opened");
  const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(stream),
                                         std::istreambuf_iterator<char>()};
  if (stream.bad()) fail("cannot read", path, "the file could not be read");
  if (bytes.size() < kPngSignature.size() ||
      std::memcmp(bytes.data(), kPngSignature.data(), kPngSignature.size()) != 0) {
    fail("cannot read", path, "not a PNG file");
  }
  if (bytes.size() > size_t(std::numeric_limits<int>::max()))
    fail("cannot read", path, "file too large");

  int width = 0;
  int height = 0;
  int channelsInFile = 0;
  // Always 4 channels out, whatever the file stores (grey, RGB, palette, 16-bit).
  const std::unique_ptr<stbi_uc, void (*)(void*)> decoded(
      stbi_load_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channelsInFile, 4),
      stbi_image_free);
  if (!decoded)
    fail("cannot read", path, std::string("corrupt PNG (") + stbi_failure_reason() + ")");

  Rgba8Image image;
  image.width = uint32_t(width);
  image.height = uint32_t(height);
  image.pixels.assign(decoded.get(), decoded.get() + size_t(width) * size_t(height) * 4);
  return image;
}

}  // namespace hmb::io
