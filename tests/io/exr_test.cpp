#include <gtest/gtest.h>

#include <cmath>
#include <limits>
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

// Distinct, non-round values so a swapped channel, layer or row cannot go unnoticed.
ImageLayer floatLayer(const std::string& name, std::vector<std::string> channels, uint32_t width,
                      uint32_t height, float seed) {
  ImageLayer layer{.name = name, .channels = std::move(channels)};
  layer.values.resize(size_t(width) * height * layer.channels.size());
  for (size_t i = 0; i < layer.values.size(); ++i) {
    layer.values[i] = seed + float(i) * 0.37f - std::sin(float(i)) * 1e-3f;
  }
  return layer;
}

ImageLayer idLayer(uint32_t width, uint32_t height) {
  ImageLayer layer{.name = "objectId", .channels = {"id"}, .isUint = true};
  layer.ids.resize(size_t(width) * height);
  for (size_t i = 0; i < layer.ids.size(); ++i) layer.ids[i] = uint32_t(i * 2654435761u);
  layer.ids.front() = 0xffffffffu;  // the full 32-bit range survives
  return layer;
}

LayeredImage renderLikeImage(uint32_t width, uint32_t height) {
  LayeredImage image{.width = width, .height = height};
  image.layers.push_back(floatLayer("", {"R", "G", "B", "A"}, width, height, 0.25f));
  image.layers.push_back(floatLayer("depth", {"Z"}, width, height, 10.0f));
  image.layers.push_back(floatLayer("normal", {"X", "Y", "Z"}, width, height, -1.0f));
  image.layers.push_back(floatLayer("velocity", {"X", "Y"}, width, height, -3.5f));
  image.layers.push_back(idLayer(width, height));
  return image;
}

void expectSameImage(const LayeredImage& expected, const LayeredImage& actual) {
  ASSERT_EQ(actual.width, expected.width);
  ASSERT_EQ(actual.height, expected.height);
  ASSERT_EQ(actual.layers.size(), expected.layers.size());
  for (const ImageLayer& want : expected.layers) {
    const ImageLayer* got = actual.find(want.name);
    ASSERT_NE(got, nullptr) << "layer '" << want.name << "'";
    EXPECT_EQ(got->channels, want.channels) << "layer '" << want.name << "'";
    EXPECT_EQ(got->isUint, want.isUint) << "layer '" << want.name << "'";
    EXPECT_EQ(got->values, want.values) << "layer '" << want.name << "'";  // bit exact
    EXPECT_EQ(got->ids, want.ids) << "layer '" << want.name << "'";
  }
}

TEST(Exr, MultiLayerRoundTripIsExact) {
  const auto path = scratchPath(".exr");
  const LayeredImage image = renderLikeImage(64, 48);
  writeExr(path, image);
  const LayeredImage readBack = readExr(path);
  expectSameImage(image, readBack);
  EXPECT_EQ(readBack.layers.front().name, "") << "the beauty layer comes first";
}

TEST(Exr, ChannelNamesInTheFileFollowTheLayerConvention) {
  const auto path = scratchPath(".exr");
  writeExr(path, renderLikeImage(4, 4));
  const std::string bytes = readBytes(path);
  // The header stores channel names as null-terminated strings.
  for (const char* name : {"R", "G", "B", "A", "depth.Z", "normal.X", "normal.Y", "normal.Z",
                           "velocity.X", "velocity.Y", "objectId.id"}) {
    EXPECT_NE(bytes.find(std::string(name) + '\0'), std::string::npos) << name;
  }
}

TEST(Exr, OddSizesRoundTrip) {
  for (const auto& [width, height] : {std::pair{1u, 1u}, std::pair{7u, 3u}, std::pair{3u, 7u}}) {
    const auto path = scratchPath(testing::sizeSuffix(width, height, ".exr"));
    const LayeredImage image = renderLikeImage(width, height);
    writeExr(path, image);
    SCOPED_TRACE(path.filename().string());
    expectSameImage(image, readExr(path));
  }
}

TEST(Exr, NonCanonicalChannelOrderComesBackCanonicalWithMatchingData) {
  const auto path = scratchPath(".exr");
  LayeredImage image{.width = 2, .height = 1};
  image.layers.push_back(
      {.name = "", .channels = {"A", "B", "G", "R"}, .values = {4, 3, 2, 1, 40, 30, 20, 10}});
  writeExr(path, image);
  const LayeredImage readBack = readExr(path);
  ASSERT_EQ(readBack.layers.size(), 1u);
  EXPECT_EQ(readBack.layers[0].channels, (std::vector<std::string>{"R", "G", "B", "A"}));
  EXPECT_EQ(readBack.layers[0].values, (std::vector<float>{1, 2, 3, 4, 10, 20, 30, 40}));
}

TEST(Exr, NonFiniteValuesAreWrittenAsZero) {
  const auto path = scratchPath(".exr");
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  LayeredImage image{.width = 3, .height = 2};
  image.layers.push_back(
      {.name = "depth",
       .channels = {"Z"},
       .values = {nan, kInf, -kInf, 1.5f, -2.0f, std::numeric_limits<float>::max()}});
  writeExr(path, image);
  EXPECT_TRUE(std::isnan(image.layers[0].values[0])) << "the caller's data is left alone";
  const LayeredImage readBack = readExr(path);
  ASSERT_NE(readBack.find("depth"), nullptr);
  EXPECT_EQ(readBack.find("depth")->values,
            (std::vector<float>{0.0f, 0.0f, 0.0f, 1.5f, -2.0f, std::numeric_limits<float>::max()}));
}

TEST(Exr, MissingFileThrows) {
  const auto path = scratchPath(".exr");
  expectError([&] { readExr(path); }, path.string());
}

TEST(Exr, CorruptFileThrows) {
  const auto path = scratchPath(".exr");
  writeBytes(path, randomBytes(4096, 7));
  expectError([&] { readExr(path); }, path.string());
}

TEST(Exr, EmptyFileThrows) {
  const auto path = scratchPath(".exr");
  writeBytes(path, "");
  expectError([&] { readExr(path); }, path.string());
}

TEST(Exr, TruncatedFileThrows) {
  const auto path = scratchPath(".exr");
  writeExr(path, renderLikeImage(64, 64));
  const std::string bytes = readBytes(path);
  writeBytes(path, bytes.substr(0, bytes.size() / 2));
  expectError([&] { readExr(path); }, path.string());
}

TEST(Exr, DirectoryInsteadOfFileThrows) {
  const auto path = scratchPath("_dir");
  std::filesystem::create_directories(path);
  expectError([&] { readExr(path); }, path.string());
  expectError([&] { writeExr(path, renderLikeImage(2, 2)); }, path.string());
}

TEST(Exr, UnwritablePathThrows) {
  const auto path = scratchPath("_missing_dir") / "out.exr";
  expectError([&] { writeExr(path, renderLikeImage(2, 2)); }, path.string());
}

TEST(Exr, SizeMismatchThrows) {
  const auto path = scratchPath(".exr");
  LayeredImage image = renderLikeImage(5, 4);
  image.layers[2].values.pop_back();  // normal
  expectError([&] { writeExr(path, image); }, "normal");
  image = renderLikeImage(5, 4);
  image.layers[4].ids.push_back(1);  // objectId
  expectError([&] { writeExr(path, image); }, "objectId");
  image = renderLikeImage(5, 4);
  image.layers[4].isUint = false;  // ids given, float values expected
  expectError([&] { writeExr(path, image); }, "objectId");
  EXPECT_FALSE(std::filesystem::exists(path)) << "nothing is written for invalid input";
}

TEST(Exr, EmptySizeThrows) {
  const auto path = scratchPath(".exr");
  LayeredImage image{.width = 0, .height = 4};
  image.layers.push_back({.name = "depth", .channels = {"Z"}});
  expectError([&] { writeExr(path, image); }, path.string());
  image.width = 4;
  image.height = 0;
  expectError([&] { writeExr(path, image); }, "empty");
}

TEST(Exr, DuplicateChannelNamesThrow) {
  const auto path = scratchPath(".exr");
  LayeredImage image{.width = 1, .height = 1};
  image.layers.push_back({.name = "depth", .channels = {"Z", "Z"}, .values = {1, 2}});
  expectError([&] { writeExr(path, image); }, "depth.Z");
  image.layers = {{.name = "depth", .channels = {"Z"}, .values = {1}},
                  {.name = "depth", .channels = {"Z"}, .values = {2}}};
  expectError([&] { writeExr(path, image); }, "duplicate");
}

TEST(Exr, InvalidLayoutsThrow) {
  const auto path = scratchPath(".exr");
  LayeredImage image{.width = 1, .height = 1};
  expectError([&] { writeExr(path, image); }, "no layers");
  image.layers = {{.name = "depth", .channels = {}}};
  expectError([&] { writeExr(path, image); }, "no channels");
  image.layers = {{.name = "depth", .channels = {"a.b"}, .values = {1}}};
  expectError([&] { writeExr(path, image); }, "a.b");
  image.layers = {{.name = "depth", .channels = {""}, .values = {1}}};
  expectError([&] { writeExr(path, image); }, "invalid channel");
}

TEST(Exr, ErrorsAreHmbErrors) {
  // The CLI catches hmb::Error only; OpenEXR's own exceptions must never escape.
  const auto path = scratchPath(".exr");
  writeBytes(path, "v/1\x01garbage");
  EXPECT_THROW(readExr(path), hmb::Error);
}

}  // namespace
}  // namespace hmb::io
