// hmblur compare as a user meets it: the table, the JSON, error images, one-line errors.
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "runtime/io/image_files.h"
#include "tests/cli/cli_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

// A 32x24 grey frame with a bright square at `squareX`: moving the square is the "motion".
io::Rgba8Image frame(uint32_t squareX, uint8_t squareValue = 230, uint32_t width = 32, uint32_t height = 24) {
  io::Rgba8Image image{.width = width, .height = height};
  image.pixels.resize(size_t(width) * height * 4);
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool inSquare = x >= squareX && x < squareX + 8 && y >= 8 && y < 16;
      uint8_t* pixel = image.pixels.data() + (size_t(y) * width + x) * 4;
      pixel[0] = pixel[1] = inSquare ? squareValue : 60;
      pixel[2] = inSquare ? 40 : 60;
      pixel[3] = 255;
    }
  return image;
}

// The reference blurs the square over x in [10, 22); the sharp frame has it at [14, 22).
io::Rgba8Image blurredFrame() {
  io::Rgba8Image image = frame(14);
  for (uint32_t y = 8; y < 16; ++y)
    for (uint32_t x = 10; x < 14; ++x) {
      uint8_t* pixel = image.pixels.data() + (size_t(y) * image.width + x) * 4;
      pixel[0] = pixel[1] = uint8_t(60 + (230 - 60) * (x - 9) / 5);
      pixel[2] = 50;
    }
  return image;
}

TEST(CompareCli, PrintsATableAndWritesJsonAndErrorImages) {
  const fs::path dir = tempDir("compare_table");
  io::writePng(dir / "reference.png", blurredFrame());
  io::writePng(dir / "sharp.png", frame(14));
  io::writePng(dir / "method.png", frame(12));
  const CliRun run = hmblur("--quiet compare " + (dir / "reference.png").string() + " " + (dir / "method.png").string() +
                            " " + (dir / "sharp.png").string() + " --sharp " + (dir / "sharp.png").string() +
                            " --json " + (dir / "metrics.json").string() + " --error-images " +
                            (dir / "errors").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const char* text : {"PSNR dB", "SSIM", "FLIP", "blur region: 32 pixels", "method.png", "sharp.png"})
    EXPECT_NE(run.output.find(text), std::string::npos) << text << "\n" << run.output;

  std::ifstream in(dir / "metrics.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["tool"], "hmblur compare");
  EXPECT_EQ(json["blur_region_pixels"], 32);
  EXPECT_EQ(json["settings"]["flip"]["pixels_per_degree"], 67.0);
  ASSERT_EQ(json["images"].size(), 2u);
  for (const auto& image : json["images"]) {
    const auto& metrics = image["metrics"];
    EXPECT_TRUE(metrics["frame"]["psnr_db"].is_number()) << metrics.dump();
    EXPECT_TRUE(metrics["frame"]["ssim"].is_number()) << metrics.dump();
    EXPECT_GT(metrics["frame"]["flip"].get<double>(), 0.0);
    ASSERT_TRUE(metrics["region"].is_object()) << metrics.dump();
    EXPECT_EQ(metrics["region"]["pixels"], 32);
    // Both images are wrong where the reference is blurred, worse there than over the frame.
    EXPECT_LT(metrics["region"]["psnr_db"].get<double>(), metrics["frame"]["psnr_db"].get<double>());
    const io::Rgba8Image error = io::readPng(image["error_image"].get<std::string>());
    EXPECT_EQ(error.width, 32u);
    EXPECT_EQ(error.height, 24u);
  }
}

TEST(CompareCli, IdenticalImagesShowAnInfinitePsnrAndWriteNull) {
  const fs::path dir = tempDir("compare_identical");
  io::writePng(dir / "a.png", frame(5));
  const CliRun run = hmblur("--quiet compare " + (dir / "a.png").string() + " " + (dir / "a.png").string() +
                            " --json " + (dir / "m.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("inf"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("blur region"), std::string::npos) << run.output;  // no --sharp, no region
  std::ifstream in(dir / "m.json");
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_TRUE(json["images"][0]["metrics"]["frame"]["psnr_db"].is_null());
  EXPECT_EQ(json["images"][0]["metrics"]["frame"]["mse"], 0.0);
  EXPECT_TRUE(json["images"][0]["metrics"]["region"].is_null());
  EXPECT_TRUE(json["sharp"].is_null());
}

// Metrics judge what a PNG shows: an EXR of the same render is quantized as its PNG is, so the
// two score the same, as reference or as test. The tolerance allows the host's display
// transform and the device's to round a pixel to neighbouring codes.
TEST(CompareCli, APngAndAnExrOfTheSameRenderScoreTheSame) {
  const fs::path dir = tempDir("compare_formats");
  const std::string size = " --scene temple --width 48 --height 27 --out ";
  for (const char* name : {"reference.exr", "reference.png"})
    ASSERT_EQ(hmblur("--quiet render --method reference --spp 4" + size + (dir / name).string()).exitCode, 0);
  for (const char* name : {"post.exr", "post.png"})
    ASSERT_EQ(hmblur("--quiet render --method postprocess" + size + (dir / name).string()).exitCode, 0);
  for (const char* reference : {"reference.exr", "reference.png"}) {
    const fs::path json = dir / (std::string(reference) + ".json");
    const CliRun run = hmblur("--quiet compare " + (dir / reference).string() + " " + (dir / "post.exr").string() +
                              " " + (dir / "post.png").string() + " --json " + json.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    nlohmann::json metrics;
    std::ifstream(json) >> metrics;
    const auto& exr = metrics["images"][0]["metrics"]["frame"];
    const auto& png = metrics["images"][1]["metrics"]["frame"];
    EXPECT_GT(exr["flip"].get<double>(), 0.001) << reference;  // the post-process frame is not the reference
    EXPECT_NEAR(exr["flip"].get<double>(), png["flip"].get<double>(), 1e-4) << reference;
    EXPECT_NEAR(exr["psnr_db"].get<double>(), png["psnr_db"].get<double>(), 0.01) << reference;
    EXPECT_NEAR(exr["ssim"].get<double>(), png["ssim"].get<double>(), 1e-4) << reference;
  }
}

TEST(CompareCli, MissingFileIsAOneLineError) {
  const fs::path dir = tempDir("compare_missing");
  io::writePng(dir / "a.png", frame(5));
  expectOneLineError(hmblur("--quiet compare " + (dir / "nope.png").string() + " " + (dir / "a.png").string()),
                     "no such file");
  expectOneLineError(hmblur("--quiet compare " + (dir / "a.png").string() + " " + (dir / "nope.exr").string()),
                     "nope.exr");
  expectOneLineError(hmblur("--quiet compare " + (dir / "a.png").string() + " " + (dir / "a.png").string() +
                            " --sharp " + (dir / "nope.png").string()),
                     "no such file");
}

TEST(CompareCli, SizeMismatchIsAOneLineError) {
  const fs::path dir = tempDir("compare_size");
  io::writePng(dir / "a.png", frame(5));
  io::writePng(dir / "small.png", frame(5, 230, 16, 24));
  const CliRun run = hmblur("--quiet compare " + (dir / "a.png").string() + " " + (dir / "small.png").string());
  expectOneLineError(run, "is 16x24 but the reference");
  EXPECT_NE(run.output.find("32x24"), std::string::npos) << run.output;
}

TEST(CompareCli, BadArgumentsFail) {
  const fs::path dir = tempDir("compare_arguments");
  io::writePng(dir / "a.png", frame(5));
  const std::string a = (dir / "a.png").string();
  expectOneLineError(hmblur("--quiet compare " + a + " " + a + " --json metrics.txt"), "must end in .json");
  // Missing folders are made; a folder that cannot be (a file stands in the way) is an error.
  expectOneLineError(hmblur("--quiet compare " + a + " " + a + " --json " + (dir / "a.png" / "m.json").string()),
                     "cannot create the folder");
  EXPECT_EQ(hmblur("--quiet compare " + a + " " + a + " --json " + (dir / "new" / "m.json").string()).exitCode, 0);
  EXPECT_TRUE(fs::exists(dir / "new" / "m.json"));
  expectOneLineError(hmblur("--quiet compare " + a + " " + a + " --ppd 0"), "--ppd");
  EXPECT_NE(hmblur("compare " + a).exitCode, 0);  // no image to measure
  EXPECT_NE(hmblur("compare").exitCode, 0);
}

TEST(CompareCli, HelpNamesTheOptions) {
  const CliRun run = hmblur("compare --help");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  for (const char* option : {"--sharp", "--json", "--error-images", "--ppd"})
    EXPECT_NE(run.output.find(option), std::string::npos) << option;
  EXPECT_NE(hmblur("--help").output.find("compare"), std::string::npos);
}

}  // namespace
}  // namespace hmb::test
