// The example programs run as a user would, with validation on (a validation message is exit
// code 3): render_frame renders through the library API alone; engine_backend draws its own
// G-buffer on its own device and has the library blur it in its own command buffer.
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/io/image_files.h"
#include "tests/cli/cli_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

CliRun example(const std::string& args) { return runProgram(HMB_EXAMPLE_PATH, "--validation " + args); }

// The engine example's line per frame, "frame-NN: blurred in F ms (pass T, pass xN T, ...)":
// each pass named once, and the passes (printed to 0.01 ms) adding up to the frame.
void expectFrameLinesNameEachPassOnceAddingUp(const std::string& output, size_t frames) {
  std::istringstream lines(output);
  std::string line;
  size_t seen = 0;
  while (std::getline(lines, line)) {
    const size_t at = line.find(": blurred in ");
    if (at == std::string::npos) continue;
    ++seen;
    const double frame = std::stod(line.substr(at + 13));
    const size_t open = line.find('('), close = line.rfind(')');
    ASSERT_TRUE(open != std::string::npos && close > open) << line;
    std::istringstream entries(line.substr(open + 1, close - open - 1));
    std::set<std::string> names;
    double sum = 0.0;
    size_t passes = 0;
    for (std::string entry; std::getline(entries, entry, ',');) {
      std::istringstream words(entry);
      std::string name, word, last;
      words >> name;
      while (words >> word) last = word;
      EXPECT_TRUE(names.insert(name).second) << name << " twice in: " << line;
      sum += std::stod(last);
      ++passes;
    }
    EXPECT_NEAR(sum, frame, 0.005 * passes + 0.1 * frame) << line;
  }
  EXPECT_EQ(seen, frames) << output;
}

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

// Under the validation layer with synchronization validation, on the engine's own instance:
// frames written, blurred where the boxes move, untouched where nothing does; the hybrid (the
// engine's geometry as a scene, its own shadeHit) differs from the post-process only there too.
TEST(EngineExampleTest, BlursItsOwnGBufferWithoutAValidationMessage) {
  const fs::path dir = tempDir("engine-example");
  std::map<std::string, std::vector<io::Rgba8Image>> frames;
  for (const char* method : {"postprocess", "hybrid"}) {
    const fs::path out = dir / method;
    const CliRun run = runProgram(HMB_ENGINE_EXAMPLE_PATH,
                                  std::string("--validation --method ") + method + " --frames 2 --size 96x54 " + out.string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("frame-01: blurred in"), std::string::npos) << run.output;
    expectFrameLinesNameEachPassOnceAddingUp(run.output, 2);
    for (const char* frame : {"frame-00", "frame-01"}) {
      const io::Rgba8Image blurred = io::readPng(out / (std::string(frame) + ".png"));
      const io::Rgba8Image sharp = io::readPng(out / (std::string(frame) + "-sharp.png"));
      ASSERT_EQ(blurred.width, 96u);
      ASSERT_EQ(blurred.height, 54u);
      size_t changed = 0, changedInSky = 0;
      for (size_t i = 0; i < blurred.pixels.size(); i += 4) {
        const bool differs = std::abs(int(blurred.pixels[i]) - int(sharp.pixels[i])) > 2;
        changed += differs;
        changedInSky += differs && i / 4 < 96u * 12u;  // the top rows: sky only
      }
      EXPECT_GT(changed, 20u) << method << " " << frame;
      EXPECT_EQ(changedInSky, 0u) << method << " " << frame;
      frames[method].push_back(blurred);
    }
  }
  // The hybrid's reveal changes pixels beside the moving boxes, and nothing in the sky.
  size_t differ = 0, differInSky = 0;
  const std::vector<uint8_t>& a = frames["postprocess"][1].pixels;
  const std::vector<uint8_t>& b = frames["hybrid"][1].pixels;
  for (size_t i = 0; i < a.size(); i += 4) {
    const bool d = std::abs(int(a[i]) - int(b[i])) > 2;
    differ += d;
    differInSky += d && i / 4 < 96u * 12u;
  }
  EXPECT_GT(differ, 0u);
  EXPECT_EQ(differInSky, 0u);
  const CliRun usage = runProgram(HMB_ENGINE_EXAMPLE_PATH, "--size 0x0 " + dir.string());
  EXPECT_EQ(usage.exitCode, 2) << usage.output;
  const CliRun method = runProgram(HMB_ENGINE_EXAMPLE_PATH, "--method magic " + dir.string());
  EXPECT_EQ(method.exitCode, 2) << method.output;
}

// The engine's sky is the library's background (EngineScene::setBackground): hybrid-rays'
// rays that hit nothing, along the floor's far edge past the turning box, see it, where they
// saw black (17 to 33 black pixels a frame over the sky at this size before).
TEST(EngineExampleTest, RaysThatHitNothingSeeTheEnginesSky) {
  const fs::path out = tempDir("engine-example-sky");
  const CliRun run = runProgram(HMB_ENGINE_EXAMPLE_PATH, "--validation --method hybrid-rays --frames 4 --size 320x180 " +
                                                             out.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const char* frame : {"frame-00", "frame-01", "frame-02", "frame-03"}) {
    const io::Rgba8Image blurred = io::readPng(out / (std::string(frame) + ".png"));
    const io::Rgba8Image sharp = io::readPng(out / (std::string(frame) + "-sharp.png"));
    size_t sky = 0, blackOverSky = 0;
    for (size_t i = 0; i < blurred.pixels.size(); i += 4) {
      const bool skyThere = sharp.pixels[i + 2] > 200 && sharp.pixels[i] < sharp.pixels[i + 2];  // blue over red
      sky += skyThere;
      blackOverSky += skyThere && blurred.pixels[i] + blurred.pixels[i + 1] + blurred.pixels[i + 2] < 30;
    }
    EXPECT_GT(sky, 1000u) << frame;
    EXPECT_EQ(blackOverSky, 0u) << frame;
  }
}

// The example engine drawing a scene the library loads (its own graphics pipeline, the library's
// camera, base colours only: it draws no textures) against the command line's frames of the
// same scene: wherever the two sharp G-buffers agree, so do the two hybrid frames; they differ
// only on the living room's textured floor and rug.
TEST(EngineExampleTest, ItsHybridFrameIsTheCommandLinesWhereTheirGBuffersAgree) {
  const fs::path dir = tempDir("engine-example-scene");
  const CliRun run = runProgram(HMB_ENGINE_EXAMPLE_PATH, "--validation --scene living-room --frames 1 --size 160x90 " +
                                                             (dir / "engine").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("textures are not drawn"), std::string::npos) << run.output;
  for (const char* method : {"sharp", "hybrid"}) {
    const CliRun cli = hmblur(std::string("render --scene living-room --method ") + method +
                              " --width 160 --height 90 --quiet --out " + (dir / (std::string(method) + ".png")).string());
    ASSERT_EQ(cli.exitCode, 0) << cli.output;
  }
  const io::Rgba8Image engineSharp = io::readPng(dir / "engine" / "frame-00-sharp.png");
  const io::Rgba8Image engineHybrid = io::readPng(dir / "engine" / "frame-00.png");
  const io::Rgba8Image cliSharp = io::readPng(dir / "sharp.png");
  const io::Rgba8Image cliHybrid = io::readPng(dir / "hybrid.png");
  const auto differs = [](const io::Rgba8Image& a, const io::Rgba8Image& b, size_t pixel) {
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(a.pixels[4 * pixel + c]) - int(b.pixels[4 * pixel + c])) > 2) return true;
    return false;
  };
  size_t sharpAgree = 0, hybridDiffersThere = 0;
  for (size_t i = 0; i < size_t(160) * 90; ++i) {
    if (differs(engineSharp, cliSharp, i)) continue;
    ++sharpAgree;
    hybridDiffersThere += differs(engineHybrid, cliHybrid, i);
  }
  EXPECT_GT(sharpAgree, size_t(160) * 90 * 7 / 10);  // all but the floor and the rug
  EXPECT_EQ(hybridDiffersThere, 0u) << "of " << sharpAgree << " pixels whose G-buffers agree";
}

}  // namespace
}  // namespace hmb::test
