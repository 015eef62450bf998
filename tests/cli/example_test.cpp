// The example program (examples/render_frame.cpp) renders through the library API alone; run
// as a user would, with validation on (a validation error is exit code 3).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "runtime/io/image_files.h"
#include "tests/cli/cli_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

CliRun example(const std::string& args) { return runProgram(HMB_EXAMPLE_PATH, "--validation " + args); }

TEST(LibraryExampleTest, RendersEachMethodAndReportsItsPasses) {
  const fs::path dir = tempDir("example");
  for (const char* method : {"postprocess", "hybrid"}) {
    const fs::path out = dir / (std::string(method) + ".png");
    const CliRun run = example(std::string("living-room ") + method + " " + out.string() + " 48 27");
    ASSERT_EQ(run.exitCode, 0) << run.output;
    const io::Rgba8Image png = io::readPng(out);
    EXPECT_EQ(png.width, 48u);
    EXPECT_EQ(png.height, 27u);
    EXPECT_NE(run.output.find(std::string(method) + " 48x27 on "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("  resolve-gbuffer: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("  tile-max: "), std::string::npos) << run.output;
    EXPECT_EQ(run.output.find("reveal rays") != std::string::npos, std::string(method) == "hybrid") << run.output;
  }
}

TEST(LibraryExampleTest, BadInputIsAOneLineErrorAndANonZeroExit) {
  const fs::path dir = tempDir("example-errors");
  const CliRun usage = example("living-room");
  EXPECT_EQ(usage.exitCode, 2) << usage.output;
  expectOneLineError(usage, "usage: render_frame");
  const CliRun missing = example("no-such-scene.gltf hybrid " + (dir / "x.png").string());
  EXPECT_EQ(missing.exitCode, 1) << missing.output;
  expectOneLineError(missing, "render_frame: error: ");
  const CliRun method = example("living-room magic " + (dir / "x.png").string());
  EXPECT_EQ(method.exitCode, 1) << method.output;
  expectOneLineError(method, "unknown method 'magic'");
}

}  // namespace
}  // namespace hmb::test
