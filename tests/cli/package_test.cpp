// The installed package as an engine's build uses it: `cmake --install`, then a project outside
// the tree finds it (find_package(hmblur CONFIG), hmblur::hmblur, <hmblur/hmblur.h>), builds
// and renders a frame, traces one with its own shadeHit and shadeMiss written against the
// installed hmblur/hit_shading.glsl (which its own shader compiles with too); pkg-config
// describes the same library.
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
  for (const char* file : {"include/hmblur/hmblur.h", "include/hmblur/renderer.h", "include/hmblur/hit_shading.glsl",
                           "include/hmblur/engine_motion_blur.h", "lib/cmake/hmblur/hmblurConfig.cmake",
                           "lib/pkgconfig/hmblur.pc", "bin/hmblur"})
    EXPECT_TRUE(fs::exists(prefix / file)) << file;
  // The public API is include/hmblur/ of the source tree, installed as it is and alone: no
  // pass's, method's, kernel's or command line's header.
  const fs::path publicHeaders = fs::path(HMB_CONSUMER_DIR) / "../../../include/hmblur";
  size_t installed = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(prefix / "include")) {
    if (!entry.is_regular_file()) continue;
    ++installed;
    const fs::path relative = fs::relative(entry.path(), prefix / "include/hmblur");
    EXPECT_TRUE(fs::exists(publicHeaders / relative)) << entry.path() << " is not the API's";
  }
  EXPECT_EQ(installed, size_t(std::distance(fs::directory_iterator(publicHeaders), fs::directory_iterator())));
  // Every function an installed header declares links against an installed library (or is the
  // header's own inline one).
  const CliRun symbols = runProgram("sh", quoted(fs::path(HMB_CONSUMER_DIR) / "../installed_symbols.sh") + " " +
                                              quoted(prefix) + " " + quoted(dir / "symbols"));
  ASSERT_EQ(symbols.exitCode, 0) << symbols.output;
  EXPECT_EQ(symbols.output, "") << "declared by the installed headers, defined by no installed library";
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
  // Its own shader, compiled with the installed GLSL include alone, shares its shadeHit and shadeMiss.
  EXPECT_TRUE(fs::exists(build / "shading_check.spv"));
  const CliRun run = runProgram(quoted(build / "consumer"), "");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("consumer: rendered 32x18"), std::string::npos) << run.output;

  // The same program built by a plain compiler line from pkg-config's flags, without --static
  // (the layers are static libraries: Libs names what they link), whose Cflags are the install's
  // include folder alone: no define, no path into the library's own folders.
  const std::string pkgConfig = "PKG_CONFIG_PATH=" + quoted(prefix / "lib/pkgconfig") + " pkg-config";
  const CliRun cflags = runProgram(pkgConfig, "--cflags hmblur");
  ASSERT_EQ(cflags.exitCode, 0) << cflags.output;
  EXPECT_EQ(cflags.output.find("-D"), std::string::npos) << cflags.output;
  EXPECT_EQ(cflags.output.find("include/hmblur"), std::string::npos) << cflags.output;
  EXPECT_EQ(cflags.output.find("spirv_cross"), std::string::npos) << cflags.output;
  const fs::path program = dir / "consumer-pkg-config";
  const CliRun plain = runProgram("c++", "-std=c++20 " + quoted(fs::path(HMB_CONSUMER_DIR) / "main.cpp") +
                                             " -DCONSUMER_SOURCE_DIR='\"" + std::string(HMB_CONSUMER_DIR) + "\"' -o " +
                                             quoted(program) + " $(" + pkgConfig + " --cflags --libs hmblur)");
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  const CliRun again = runProgram(quoted(program), "");
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("consumer: rendered 32x18"), std::string::npos) << again.output;
}

// The library alone (HMB_BUILD_TOOLS=OFF) configures where CLI11, OpenEXR, FreeType and
// fontconfig cannot be found, and has no command-line target; with the tools it needs them.
TEST(PackageTest, TheLibraryAloneConfiguresWithoutTheToolsLibraries) {
  const fs::path dir = tempDir("library-alone");
  const std::string cmake = HMB_CMAKE_COMMAND;
  const std::string hidden =
      " -DCMAKE_DISABLE_FIND_PACKAGE_CLI11=ON -DCMAKE_DISABLE_FIND_PACKAGE_OpenEXR=ON"
      " -DCMAKE_DISABLE_FIND_PACKAGE_Freetype=ON -DCMAKE_DISABLE_FIND_PACKAGE_Fontconfig=ON";
  const CliRun alone = runProgram(cmake, "-S " + quoted(HMB_SOURCE_DIR) + " -B " + quoted(dir / "alone") +
                                             " -DHMB_BUILD_TOOLS=OFF" + hidden);
  ASSERT_EQ(alone.exitCode, 0) << alone.output;
  const CliRun targets = runProgram(cmake, "--build " + quoted(dir / "alone") + " --target help");
  EXPECT_NE(targets.output.find("engine_backend"), std::string::npos) << targets.output;
  EXPECT_NE(targets.output.find("... hmb\n"), std::string::npos) << targets.output;
  EXPECT_EQ(targets.output.find("... hmblur\n"), std::string::npos) << targets.output;
  EXPECT_EQ(targets.output.find("hmb_io"), std::string::npos) << targets.output;
  const CliRun tools = runProgram(cmake, "-S " + quoted(HMB_SOURCE_DIR) + " -B " + quoted(dir / "tools") + hidden);
  EXPECT_NE(tools.exitCode, 0) << "the tools found the libraries they were denied";
}

}  // namespace
}  // namespace hmb::test
