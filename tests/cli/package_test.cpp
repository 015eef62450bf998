// The installed package as an engine's build uses it: `cmake --install`, then a project outside
// the tree finds it (find_package(hmblur CONFIG), hmblur::hmblur, <hmblur/hmblur.h>), builds
// and renders a frame; pkg-config describes the same library.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "tests/cli/cli_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

std::string quoted(const fs::path& path) { return "'" + path.string() + "'"; }

TEST(PackageTest, AProjectOutsideTheTreeBuildsAgainstTheInstalledPackage) {
  const fs::path dir = tempDir("package");
  const fs::path prefix = dir / "prefix", build = dir / "consumer-build";
  const std::string cmake = HMB_CMAKE_COMMAND;

  const CliRun install = runProgram(cmake, "--install " + quoted(HMB_BUILD_DIR) + " --prefix " + quoted(prefix));
  ASSERT_EQ(install.exitCode, 0) << install.output;
  for (const char* file : {"include/hmblur/hmblur.h", "include/hmblur/runtime/renderer.h",
                           "include/hmblur/kernels/trace/trace_layout.h", "lib/cmake/hmblur/hmblurConfig.cmake",
                           "lib/pkgconfig/hmblur.pc", "bin/hmblur"})
    EXPECT_TRUE(fs::exists(prefix / file)) << file;
  EXPECT_FALSE(fs::exists(prefix / "include/hmblur/runtime/cli")) << "the command line's headers are not the API";
  // The library needs Vulkan and what the renderer truly uses: not the command line's parser,
  // nor the image files' and captions' libraries.
  for (const char* file : {"lib/cmake/hmblur/hmblurConfig.cmake", "lib/cmake/hmblur/hmblurTargets.cmake",
                           "lib/pkgconfig/hmblur.pc"}) {
    std::ifstream in(prefix / file);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (const char* dependency : {"CLI11", "OpenEXR", "Freetype", "freetype", "fontconfig", "Fontconfig"})
      EXPECT_EQ(text.find(dependency), std::string::npos) << file << " names " << dependency;
  }

  const CliRun configure = runProgram(cmake, "-S " + quoted(HMB_CONSUMER_DIR) + " -B " + quoted(build) +
                                                 " -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=" + quoted(prefix));
  ASSERT_EQ(configure.exitCode, 0) << configure.output;
  const CliRun compile = runProgram(cmake, "--build " + quoted(build));
  ASSERT_EQ(compile.exitCode, 0) << compile.output;
  const CliRun run = runProgram(quoted(build / "consumer"), "");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("consumer: rendered 32x18"), std::string::npos) << run.output;

  // The same program built by a plain compiler line from pkg-config's flags (static: the layers'
  // own dependencies too).
  const std::string pkgConfig = "PKG_CONFIG_PATH=" + quoted(prefix / "lib/pkgconfig") + " pkg-config";
  const CliRun flags = runProgram(pkgConfig, "--cflags --libs --static hmblur");
  ASSERT_EQ(flags.exitCode, 0) << flags.output;
  const fs::path program = dir / "consumer-pkg-config";
  const CliRun plain = runProgram("c++", "-std=c++20 " + quoted(fs::path(HMB_CONSUMER_DIR) / "main.cpp") + " -o " +
                                             quoted(program) + " $(" + pkgConfig + " --cflags --libs --static hmblur)");
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  const CliRun again = runProgram(quoted(program), "");
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("consumer: rendered 32x18"), std::string::npos) << again.output;
}

}  // namespace
}  // namespace hmb::test
