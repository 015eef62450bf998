#include <gtest/gtest.h>

#include <string>

#include "hmblur/error.h"
#include "runtime/io/image_files.h"
#include "tests/io/test_files.h"

namespace hmb::io {
namespace {

using testing::expectError;
using testing::randomBytes;
using testing::readBytes;
using testing::scratchPath;
using testing::writeBytes;

Rgba8Image gradientImage(uint32_t width, uint32_t height) {
  Rgba8Image image{.width = width, .height = height};
  image.pixels.resize(size_t(width) * height * 4);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = uint8_t((i * 37 + i / 4) & 0xff);
  return image;
}

TEST(Png, RoundTripIsExact) {
  for (const auto& [width, height] : {std::pair{64u, 48u}, std::pair{1u, 1u}, std::pair{7u, 3u}}) {
    const auto path = scratchPath(testing::sizeSuffix(width, height, ".png"));
    const Rgba8Image image = gradientImage(width, height);
    writePng(path, image);
    const Rgba8Image readBack = readPng(path);
    SCOPED_TRACE(path.filename().string());
    EXPECT_EQ(readBack.width, width);
    EXPECT_EQ(readBack.height, height);
    EXPECT_EQ(readBack.pixels, image.pixels);  // includes alpha 0 pixels and the row order
  }
}

TEST(Png, ReadBackOfAnRgbFileHasOpaqueAlpha) {
  // A 1x1 RGB PNG (colour type 2) holding (255, 0, 0); readPng always returns 4 channels.
  const unsigned char redPixel[] = {
      0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48,
      0x44, 0x52, 0x00, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00,
      0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00, 0x0c, 0x49, 0x44, 0x41, 0x54, 0x08,
      0xd7, 0x63, 0xf8, 0xcf, 0xc0, 0x00, 0x00, 0x03, 0x01, 0x01, 0x00, 0x18, 0xdd, 0x8d,
      0xb0, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
  const auto path = scratchPath(".png");
  writeBytes(path, std::string(reinterpret_cast<const char*>(redPixel), sizeof(redPixel)));
  const Rgba8Image image = readPng(path);
  EXPECT_EQ(image.width, 1u);
  EXPECT_EQ(image.height, 1u);
  EXPECT_EQ(image.pixels, (std::vector<uint8_t>{255, 0, 0, 255}));
}

TEST(Png, MissingFileThrows) {
  const auto path = scratchPath(".png");
  expectError([&] { readPng(path); }, path.string());
}

TEST(Png, NotAPngThrows) {
  const auto path = scratchPath(".png");
  writeBytes(path, randomBytes(1024, 11));
  expectError([&] { readPng(path); }, "not a PNG");
  writeBytes(path, "");
  expectError([&] { readPng(path); }, "not a PNG");
}

TEST(Png, CorruptPngThrows) {
  const auto path = scratchPath(".png");
  writePng(path, gradientImage(32, 32));
  std::string bytes = readBytes(path);
  bytes.resize(bytes.size() / 2);  // the signature is intact, the data is not
  writeBytes(path, bytes);
  expectError([&] { readPng(path); }, path.string());
}

TEST(Png, UnwritablePathThrows) {
  const auto path = scratchPath("_missing_dir") / "out.png";
  expectError([&] { writePng(path, gradientImage(2, 2)); }, path.string());
  const auto directory = scratchPath("_dir");
  std::filesystem::create_directories(directory);
  expectError([&] { writePng(directory, gradientImage(2, 2)); }, directory.string());
  expectError([&] { readPng(directory); }, directory.string());
}

TEST(Png, SizeMismatchThrows) {
  const auto path = scratchPath(".png");
  Rgba8Image image = gradientImage(5, 4);
  image.pixels.pop_back();
  expectError([&] { writePng(path, image); }, "expected 80");
  image = gradientImage(5, 4);
  image.width = 0;
  expectError([&] { writePng(path, image); }, "empty");
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace hmb::io
