// The hmblur executable as a user meets it: exit codes, one-line errors, files it writes.
// Every command runs with --validation, so a validation error fails it with exit code 3.
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "runtime/io/image_files.h"
#include "tests/cli/cli_harness.h"
#include "tests/scenes/gltf_writer.h"
#include "tests/scenes/malformed_corpus.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

TEST(CliTest, ListDevicesNamesAComputeDeviceAndTheProfileARenderTakesThere) {
  const CliRun run = hmblur("list-devices");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("0: "), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("no compute queue"), std::string::npos) << run.output;
  // Each device with the profile a render there would take.
  const bool profiled = run.output.find("   profile cpu") != std::string::npos ||
                        run.output.find("   profile gpu") != std::string::npos;
  EXPECT_TRUE(profiled) << run.output;
}

TEST(CliTest, ListScenesNamesTheReferenceScenes) {
  const CliRun run = hmblur("list-scenes");
  EXPECT_EQ(run.exitCode, 0) << run.output;
  for (const char* name : {"living-room", "temple", "bistro", "spinning-plate", "turntable", "spinning-box"})
    EXPECT_NE(run.output.find(name), std::string::npos) << name;
}

TEST(CliTest, RenderWritesPngExrAndAReportThatNamesEveryPass) {
  const fs::path dir = tempDir("render");
  const CliRun run = hmblur("--quiet render --scene living-room --method test-pattern --width 33 --height 17 --out " +
                         (dir / "frame.png").string() + " --report " + (dir / "report.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const io::Rgba8Image png = io::readPng(dir / "frame.png");
  EXPECT_EQ(png.width, 33u);
  EXPECT_EQ(png.height, 17u);

  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["method"], "test-pattern");
  EXPECT_EQ(report["scene"]["name"], "living-room");
  EXPECT_TRUE(report["system"].contains("LP_NUM_THREADS"));
  std::vector<std::string> names;
  for (const auto& pass : report["passes"]) names.push_back(pass["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"test-pattern", "encode-display"}));

  const CliRun exr = hmblur("--quiet render --method test-pattern --width 8 --height 8 --out " + (dir / "frame.exr").string());
  ASSERT_EQ(exr.exitCode, 0) << exr.output;
  const io::LayeredImage image = io::readExr(dir / "frame.exr");
  EXPECT_EQ(image.width, 8u);
  ASSERT_NE(image.find(""), nullptr);
}

// --device-profile forces whose choices the passes make; the report names the profile, and the
// render prints its frame's shape. A bad profile, given or from HMB_DEVICE_PROFILE, is one line.
TEST(CliTest, ADeviceProfileIsForcedReportedAndCheckedInOneLine) {
  const fs::path dir = tempDir("device_profile");
  for (const char* profile : {"cpu", "gpu"}) {
    const CliRun run = hmblur(std::string("--device-profile ") + profile +
                              " render --scene temple --method hybrid --width 48 --height 27 --out " +
                              (dir / "frame.png").string() + " --report " + (dir / "report.json").string());
    ASSERT_EQ(run.exitCode, 0) << run.output;
    EXPECT_NE(run.output.find("frame shape: "), std::string::npos) << run.output;
    std::ifstream in(dir / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["device"]["profile"]["name"], profile);
    EXPECT_EQ(report["device"]["profile"]["forced"], true);
    EXPECT_EQ(report["device"]["profile"]["raster_tile_lists"], std::string(profile) == "cpu");
    EXPECT_EQ(report["raster"]["visibility_scheme"] == "tile-lists", std::string(profile) == "cpu") << report["raster"];
    EXPECT_EQ(report["frame"]["host_waits"], 1);
    EXPECT_GT(report["frame"]["dispatches"].get<int>(), 20);
  }
  const CliRun bad = hmblur("--device-profile fast render --method sharp --width 8 --height 8 --out " +
                            (dir / "bad.png").string());
  EXPECT_EQ(bad.exitCode, 2) << bad.output;
  EXPECT_NE(bad.output.find("--device-profile"), std::string::npos) << bad.output;
  const CliRun badEnvironment = runProgram("HMB_DEVICE_PROFILE=fast " HMB_CLI_PATH,
                                           "render --method sharp --width 8 --height 8 --out " + (dir / "bad.png").string());
  EXPECT_NE(badEnvironment.exitCode, 0) << badEnvironment.output;
  EXPECT_NE(badEnvironment.output.find("HMB_DEVICE_PROFILE: device profile 'fast': expected auto, cpu or gpu"),
            std::string::npos)
      << badEnvironment.output;
  EXPECT_FALSE(fs::exists(dir / "bad.png"));
}

TEST(CliTest, FramesRenderAnImageSequenceWithOneReport) {
  const fs::path dir = tempDir("frames");
  const CliRun run = hmblur("--quiet render --scene temple --method hybrid --width 48 --height 27 --frames 239:241 " +
                            ("--out " + (dir / "temple.png").string()) + " --report " + (dir / "frames.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const char* name : {"temple.0239.png", "temple.0240.png", "temple.0241.png"}) {
    ASSERT_TRUE(fs::exists(dir / name)) << name;
    EXPECT_EQ(io::readPng(dir / name).width, 48u);
  }
  EXPECT_FALSE(fs::exists(dir / "temple.0242.png"));
  std::ifstream in(dir / "frames.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["frames"].size(), 3u);
  const double fps = report["fps"];
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(report["frames"][i]["frame"], 239 + i);
    EXPECT_NEAR(double(report["frames"][i]["time_s"]), (239 + i) / fps, 1e-6);
  }
  // The first frame builds the mesh trees; the later ones keep them and say why.
  const auto meshTrees = [&](size_t frame) {
    for (const auto& pass : report["frames"][frame]["passes"])
      if (pass["name"] == "hybrid-bvh-meshes") return pass;
    return nlohmann::json();
  };
  // Each frame's time is its own: the scene's default frame time is not reported.
  EXPECT_FALSE(report["scene"]["settings"].contains("frame_time_s")) << report["scene"].dump();
  EXPECT_EQ(meshTrees(0)["status"], "run");
  EXPECT_EQ(meshTrees(2)["status"], "skipped");
  EXPECT_FALSE(meshTrees(2)["reason"].get<std::string>().empty());

  expectOneLineError(hmblur("--quiet render --frames 5:2"), "before the first");
  expectOneLineError(hmblur("--quiet render --frames 5"), "FIRST:LAST");
  expectOneLineError(hmblur("--quiet render --frames a:b"), "FIRST:LAST");
  expectOneLineError(hmblur("--quiet render --frames 0:100000"), "at most");
  expectOneLineError(hmblur("--quiet render --frames 1:2 --frame-time 0.5"), "exclude");
}

TEST(CliTest, MissingFileIsAOneLineError) {
  expectOneLineError(hmblur("--quiet render --scene /nonexistent/scene.gltf --method test-pattern"), "no such file");
}

// Every file of the malformed-glTF corpus: one line naming the file, a non-zero exit.
TEST(CliTest, EveryMalformedCorpusFileIsAOneLineError) {
  const std::vector<fs::path> files = malformedCorpusFiles();
  for (const fs::path& path : files) {
    SCOPED_TRACE(path.filename().string());
    expectOneLineError(hmblur("--quiet render --method sharp --width 8 --height 8 --scene '" + path.string() + "'"),
                       path.string());
  }
  EXPECT_GE(files.size(), kMalformedCorpusMinFiles);
}

// A PNG or a folder given as the scene, a glTF 1.0 file and a Draco-compressed one are each
// refused saying what they are.
TEST(CliTest, FilesThatAreNotGltf2ScenesSayWhatTheyAre) {
  const fs::path dir = tempDir("not_scenes");
  io::writePng(dir / "picture.png", io::Rgba8Image{.width = 1, .height = 1, .pixels = {1, 2, 3, 255}});
  expectOneLineError(hmblur("--quiet render --scene " + (dir / "picture.png").string()), "a PNG image, not a scene");
  expectOneLineError(hmblur("--quiet render --scene " + dir.string()), "a directory, not a glTF file");
  const fs::path corpus = HMB_MALFORMED_CORPUS_DIR;
  expectOneLineError(hmblur("--quiet render --scene " + (corpus / "gltf-version-1.gltf").string()),
                     "only glTF 2.0 is supported");
  expectOneLineError(hmblur("--quiet render --scene " + (corpus / "requires-draco.gltf").string()),
                     "KHR_draco_mesh_compression (Draco-compressed geometry)");
}

TEST(CliTest, UnknownSceneIsAOneLineErrorNamingTheScenes) {
  const CliRun run = hmblur("--quiet render --scene no-such-scene --method test-pattern");
  expectOneLineError(run, "no-such-scene");
  EXPECT_NE(run.output.find("living-room"), std::string::npos) << run.output;
}

TEST(CliTest, UnknownMethodNamesTheAvailableOnes) {
  const CliRun run = hmblur("--quiet render --method magic");
  expectOneLineError(run, "unknown method 'magic'");
  EXPECT_NE(run.output.find("test-pattern"), std::string::npos) << run.output;
}

TEST(CliTest, BadSizesAreRejected) {
  expectOneLineError(hmblur("--quiet render --method test-pattern --width 0"), "empty");
  expectOneLineError(hmblur("--quiet render --method test-pattern --width 100000"), "exceeds");
  EXPECT_NE(hmblur("render --method test-pattern --width abc").exitCode, 0);
  EXPECT_NE(hmblur("render --method test-pattern --height -5").exitCode, 0);
}

// One rule for every output: missing folders are made, and a place that cannot be written is
// an error before anything is loaded or rendered.
TEST(CliTest, BadOutputPathsFailBeforeRendering) {
  const fs::path dir = tempDir("outputs");
  std::ofstream(dir / "file.txt") << "a file, not a folder";
  expectOneLineError(hmblur("--quiet render --method test-pattern --out frame.bmp"), "must end in .exr or .png");
  expectOneLineError(hmblur("--quiet render --method test-pattern --report report.txt"), ".json");
  // A 64-spp reference of the living room takes seconds; the error must come at once, before
  // the scene is loaded (the progress lines would show it).
  const CliRun blocked = hmblur("render --method reference --spp 64 --out " + (dir / "file.txt" / "frame.png").string());
  expectOneLineError(blocked, "cannot create the folder");
  EXPECT_EQ(blocked.output.find("loading scene"), std::string::npos) << blocked.output;
  expectOneLineError(hmblur("--quiet render --method test-pattern --width 8 --height 8 --report " +
                            (dir / "file.txt" / "r.json").string()),
                     "cannot create the folder");
  fs::create_directories(dir / "folder.png");
  expectOneLineError(hmblur("--quiet render --method test-pattern --out " + (dir / "folder.png").string()),
                     "is a folder");
  expectOneLineError(hmblur("--quiet demo --out-dir " + (dir / "file.txt").string()), "is a file");

  const CliRun made = hmblur("--quiet render --method test-pattern --width 8 --height 8 --out " +
                             (dir / "new" / "deeper" / "frame.png").string());
  ASSERT_EQ(made.exitCode, 0) << made.output;
  EXPECT_TRUE(fs::exists(dir / "new" / "deeper" / "frame.png"));
}

// Without --out the image still gets written, under a name the command prints.
TEST(CliTest, RenderWithoutOutWritesADefaultNameAndSaysWhere) {
  const fs::path dir = tempDir("default_out");
  const CliRun run = runProgram("cd " + dir.string() + " && " + std::string(HMB_CLI_PATH),
                                "--validation render --scene temple --method sharp --width 16 --height 9");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir / "temple-sharp.png"));
  EXPECT_NE(run.output.find("temple-sharp.png"), std::string::npos) << run.output;
}

// The default method renders the scene's G-buffer: its EXR carries the AOVs, its report the
// rasterizer's visibility scheme.
TEST(CliTest, SharpRenderWritesAovLayersAndTheVisibilityScheme) {
  const fs::path dir = tempDir("sharp");
  const CliRun run = hmblur("--quiet render --scene temple --width 40 --height 24 --out " +
                            (dir / "frame.exr").string() + " --report " + (dir / "report.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const io::LayeredImage image = io::readExr(dir / "frame.exr");
  for (const char* layer : {"", "depth", "normal", "velocity", "objectId"})
    EXPECT_NE(image.find(layer), nullptr) << layer;
  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["method"], "sharp");
  EXPECT_TRUE(report["raster"]["visibility_scheme"].is_string()) << report.dump();
  EXPECT_GT(report["raster"]["setup_triangles"].get<int>(), 0);
}

// What `args` writes on stderr alone.
std::string stderrOf(const std::string& args) {
  return runProgram("sh", "-c '" + std::string(HMB_CLI_PATH) + " --validation " + args + " 2>&1 1>/dev/null'").output;
}

// A frame where nothing moves on screen gives every method the sharp frame: said on stderr,
// with the span of the animation's keys; not said for a frame that moves, nor under --quiet.
TEST(CliTest, AStillFrameSaysSoOnStderr) {
  const fs::path dir = tempDir("still");
  const std::string render = "render --scene living-room --method postprocess --width 32 --height 18 --out " +
                             (dir / "frame.png").string();
  const std::string still = stderrOf(render + " --frame-time 0.45");
  EXPECT_NE(still.find("warning: nothing moves on screen at t = 0.45 s: every method gives the sharp frame; the "
                       "animation's keys span 0 to 0.4 s"),
            std::string::npos)
      << still;
  EXPECT_EQ(stderrOf(render + " --frame-time 0.2").find("nothing moves"), std::string::npos);
  EXPECT_EQ(stderrOf("--quiet " + render + " --frame-time 0.45"), "");
  // The living room at 120 fps: frames 54-56 are 0.45-0.467 s, after the vase stopped.
  const std::string frames = stderrOf("render --scene living-room --method sharp --width 16 --height 9 --frames 54:56 --out " +
                                      (dir / "seq.png").string());
  EXPECT_NE(frames.find("nothing moves on screen at t = "), std::string::npos) << frames;
  EXPECT_EQ(frames.find("nothing moves", frames.find("nothing moves") + 1), std::string::npos)
      << "once for the sequence: " << frames;
}

// A render lists its passes with --verbose; else one line counts them.
TEST(CliTest, PassesAreListedWithVerbose) {
  const fs::path dir = tempDir("verbose");
  const std::string render = "render --scene temple --method postprocess --width 32 --height 18 --out " +
                             (dir / "frame.png").string();
  const CliRun plain = hmblur(render);
  ASSERT_EQ(plain.exitCode, 0) << plain.output;
  EXPECT_NE(plain.output.find("  passes: "), std::string::npos) << plain.output;
  EXPECT_NE(plain.output.find("(--verbose lists them)"), std::string::npos) << plain.output;
  EXPECT_EQ(plain.output.find("  tile-max: "), std::string::npos) << plain.output;
  const CliRun verbose = hmblur("--verbose " + render);
  ASSERT_EQ(verbose.exitCode, 0) << verbose.output;
  EXPECT_NE(verbose.output.find("  tile-max: "), std::string::npos) << verbose.output;
  EXPECT_NE(verbose.output.find("  encode-display: "), std::string::npos) << verbose.output;
}

// demo --scene renders a scene of the user's (a reference scene or a glTF file) at its frame
// time, its outputs named after the file's stem.
TEST(CliTest, DemoTakesTheUsersScene) {
  const fs::path dir = tempDir("demo_scene");
  const CliRun run = hmblur("--quiet demo --scene temple --frame-time 1.5 --width 32 --height 18 --spp 4 --out-dir " +
                            dir.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir / "temple-strip.png"));
  EXPECT_TRUE(fs::exists(dir / "temple-hybrid-rays.png"));
  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["scene"]["name"], "temple") << report["scene"].dump();
  for (const auto& method : report["methods"]) EXPECT_FLOAT_EQ(method["frame_time_s"].get<float>(), 1.5f) << method.dump();

  scene::test::GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({scene::test::addQuadPrimitive(w)})}})});
  const std::string file = w.writeGltf(dir / "quad.gltf").string();
  const CliRun quad = hmblur("--quiet demo --scene " + file + " --width 16 --height 9 --spp 2 --out-dir " +
                             (dir / "quad").string());
  ASSERT_EQ(quad.exitCode, 0) << quad.output;
  EXPECT_TRUE(fs::exists(dir / "quad" / "quad-strip.png"));
  // Nothing moves in it: the reference differs from the sharp frame only where the raster and
  // the ray trace part on a silhouette, which is no blur: the blur region is empty.
  std::ifstream quadIn(dir / "quad" / "report.json");
  const nlohmann::json quadReport = nlohmann::json::parse(quadIn);
  for (const auto& method : quadReport["methods"])
    if (method.contains("metrics")) {
      EXPECT_EQ(method["metrics"]["region_pixels"], 0) << method["metrics"].dump();
      EXPECT_TRUE(method["metrics"]["region"].is_null()) << method["metrics"].dump();
    }
  expectOneLineError(hmblur("--quiet demo --scene " + (dir / "missing.gltf").string() + " --out-dir " +
                            (dir / "missing").string()),
                     "missing.gltf");
}

TEST(CliTest, DeviceOutOfRangeIsAOneLineError) {
  expectOneLineError(hmblur("--quiet --device 99 render --method test-pattern --width 4 --height 4"), "--device 99");
}

TEST(CliTest, DemoWritesImagesAndAReport) {
  const fs::path dir = tempDir("demo");
  const CliRun run = hmblur("--quiet demo --width 32 --height 18 --out-dir " + dir.string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(run.output, "");  // --quiet: nothing but errors
  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_FALSE(report["methods"].empty());
  for (const auto& method : report["methods"]) {
    for (const auto& image : method["images"]) EXPECT_TRUE(fs::exists(image.get<std::string>())) << image;
    // Every method but the judge is measured against the reference.
    EXPECT_EQ(method.contains("metrics"), method["method"] != "reference") << method["method"];
  }
  const io::Rgba8Image strip = io::readPng(report["strip"]["image"].get<std::string>());
  EXPECT_EQ(strip.width, 32u * report["strip"]["order"].size());
  // Under the panels a band holds each one's caption (method, warm time, PSNR): light text on
  // dark grey.
  ASSERT_GT(strip.height, 18u);
  EXPECT_TRUE(report["strip"]["captioned"].get<bool>());
  size_t lit = 0;
  for (size_t i = size_t(18) * strip.width * 4; i < strip.pixels.size(); i += 4) lit += strip.pixels[i] > 128;
  EXPECT_GT(lit, 20u);
  for (const auto& method : report["methods"]) {
    EXPECT_TRUE(method["timing"]["median_ms"].is_number()) << method.dump();
    EXPECT_TRUE(method["timing"]["cold_ms"].is_number()) << method.dump();
  }
  // The paper's hybrid and the shutter-ray extension side by side, each frame over
  // post-process's of the same run.
  const nlohmann::json& methods = report["hybrid_methods"]["methods"];
  ASSERT_EQ(methods.size(), 2u) << report.dump();
  EXPECT_EQ(methods[0]["method"], "hybrid");
  EXPECT_EQ(methods[1]["method"], "hybrid-rays");
  for (const auto& method : methods) {
    EXPECT_GT(method["x_postprocess"].get<double>(), 0.0) << method.dump();
    EXPECT_GT(method["frame_ms"].get<double>(), 0.0) << method.dump();
  }
  EXPECT_GT(report["hybrid_methods"]["extension_buys"]["x_paper_frame"].get<double>(), 0.0) << report.dump();
}

// The reference with its settings in the report, and another method measured against it.
TEST(CliTest, ReferenceRenderAndMetricsAgainstIt) {
  const fs::path dir = tempDir("reference");
  const std::string size = " --width 40 --height 24";
  CliRun run = hmblur("--quiet render --scene living-room --method reference --spp 8 --seed 3" + size + " --out " +
                      (dir / "reference.exr").string() + " --report " + (dir / "reference.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  nlohmann::json report;
  std::ifstream(dir / "reference.json") >> report;
  EXPECT_EQ(report["settings"]["spp"], 8);
  EXPECT_EQ(report["settings"]["seed"], 3);
  EXPECT_EQ(report["settings"]["samples_done"], 8);
  // Only pixels the moving vase crosses take the later samples: the report counts what was taken.
  const uint64_t pixels = 40 * 24, moving = report["settings"]["moving_pixels"].get<uint64_t>();
  EXPECT_GT(moving, 0u);
  EXPECT_LT(moving, pixels);
  EXPECT_EQ(report["settings"]["pixel_samples"].get<uint64_t>(), pixels + 7 * moving);

  run = hmblur("--quiet render --scene living-room --method sharp" + size + " --reference " +
               (dir / "reference.exr").string() + " --report " + (dir / "sharp.json").string() + " --error-image " +
               (dir / "error.png").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::ifstream(dir / "sharp.json") >> report;
  ASSERT_TRUE(report.contains("metrics")) << report.dump();
  EXPECT_GT(report["metrics"]["frame"]["psnr_db"].get<double>(), 10.0);
  EXPECT_GT(report["metrics"]["region_pixels"].get<int>(), 0);  // the vase moves: a blur region exists
  EXPECT_EQ(io::readPng(dir / "error.png").width, 40u);

  expectOneLineError(hmblur("--quiet render --scene living-room --method sharp" + size + " --reference " +
                            (dir / "missing.exr").string()),
                     "missing.exr");
  expectOneLineError(hmblur("--quiet render --scene living-room --method sharp --width 41 --height 24 --reference " +
                            (dir / "reference.exr").string()),
                     "40x24");
  expectOneLineError(hmblur("--quiet render --method reference --spp 0" + size), "spp must be");
  expectOneLineError(hmblur("--quiet render --method reference --checkpoint /nonexistent-dir/c.bin" + size),
                     "does not exist");
}

TEST(CliTest, PostProcessSettingsReachTheReportAndBadOnesFailInOneLine) {
  const fs::path dir = tempDir("postprocess");
  const CliRun run = hmblur("--quiet render --scene temple --method postprocess --range centered --samples 9 "
                            "--tile-size 16 --width 50 --height 30 --report " + (dir / "report.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  nlohmann::json report;
  std::ifstream(dir / "report.json") >> report;
  EXPECT_EQ(report["settings"]["range"], "centered");
  EXPECT_EQ(report["settings"]["samples"], 9);
  EXPECT_EQ(report["settings"]["tile_size"], 16);
  EXPECT_EQ(report["settings"]["foreground_boost"], 1.0);
  EXPECT_FLOAT_EQ(report["settings"]["soft_z_extent"].get<float>(), 0.03f);  // the temple's own
  EXPECT_EQ(report["settings"]["time_slices"], 1);
  EXPECT_EQ(report["settings"]["motion_path"], "linear");
  // The curved path: named in the report, its two passes run.
  for (const char* method : {"postprocess", "hybrid"}) {
    const CliRun curved = hmblur("--quiet render --scene temple --method " + std::string(method) +
                                 " --motion-path curved --width 50 --height 30 --report " + (dir / "curved.json").string());
    ASSERT_EQ(curved.exitCode, 0) << curved.output;
    nlohmann::json curvedReport;
    std::ifstream(dir / "curved.json") >> curvedReport;
    EXPECT_EQ(curvedReport["settings"]["motion_path"], "curved") << method;
    size_t pathPasses = 0;
    for (const nlohmann::json& pass : curvedReport["passes"])
      if (pass["name"] == "transform-shutter-path" || pass["name"] == "resolve-shutter-path") {
        EXPECT_EQ(pass["status"], "run") << method << " " << pass.dump();
        ++pathPasses;
      }
    EXPECT_EQ(pathPasses, 2u) << method;
  }
  expectOneLineError(hmblur("--quiet render --method postprocess --motion-path curved --range centered --width 8 "
                            "--height 8"),
                     "curved motion path");
  expectOneLineError(hmblur("--quiet render --method postprocess --motion-path bent --width 8 --height 8"), "bent");
  // Time slices: the report names them, each gather's exposure is a slice's, the seed the first slice's.
  const CliRun sliced = hmblur("--quiet render --scene temple --method hybrid --time-slices 3 --seed 5 --width 50 "
                               "--height 30 --report " + (dir / "sliced.json").string());
  ASSERT_EQ(sliced.exitCode, 0) << sliced.output;
  nlohmann::json slicedReport;
  std::ifstream(dir / "sliced.json") >> slicedReport;
  EXPECT_EQ(slicedReport["settings"]["time_slices"], 3);
  EXPECT_EQ(slicedReport["settings"]["seed"], 5);
  EXPECT_FLOAT_EQ(slicedReport["settings"]["exposure_s"].get<float>(),
                  slicedReport["scene"]["settings"]["exposure_s"].get<float>() / 3.0f);
  expectOneLineError(hmblur("--quiet render --method postprocess --filter magic --width 8 --height 8"), "magic");
  expectOneLineError(hmblur("--quiet render --method postprocess --samples 0 --width 8 --height 8"), "samples");
  expectOneLineError(hmblur("--quiet render --method postprocess --neighborhood 2 --width 8 --height 8"),
                     "neighbo");
}

// The hybrid's foreground boost falls with the speed by default; a constant chosen replaces
// that law, and so does a k chosen for post-process; both chosen is a one-line error.
TEST(CliTest, TheForegroundBoostIsAConstantOrFallsWithTheSpeed) {
  const fs::path dir = tempDir("boost");
  const auto boostOf = [&](const std::string& options) {
    const fs::path report = dir / "report.json";
    const CliRun run = hmblur("--quiet render --scene temple --width 40 --height 24 " + options + " --report " +
                              report.string());
    EXPECT_EQ(run.exitCode, 0) << options << ": " << run.output;
    nlohmann::json json;
    std::ifstream(report) >> json;
    return std::pair(json["settings"]["foreground_boost"], json["settings"]["foreground_boost_pixels"]);
  };
  using nlohmann::json;
  EXPECT_EQ(boostOf("--method hybrid"), std::pair(json(nullptr), json(80.0)));
  EXPECT_EQ(boostOf("--method hybrid --foreground-boost 3"), std::pair(json(3.0), json(nullptr)));
  EXPECT_EQ(boostOf("--method hybrid --foreground-boost-pixels 20"), std::pair(json(nullptr), json(20.0)));
  EXPECT_EQ(boostOf("--method postprocess"), std::pair(json(30.0), json(nullptr)));
  EXPECT_EQ(boostOf("--method postprocess --foreground-boost-pixels 40"), std::pair(json(nullptr), json(40.0)));
  expectOneLineError(hmblur("--quiet render --method hybrid --foreground-boost 3 --foreground-boost-pixels 40 "
                            "--width 8 --height 8"),
                     "exclude each other");
  expectOneLineError(hmblur("--quiet render --method postprocess --foreground-boost-pixels 0 --width 8 --height 8"),
                     "foreground-boost-pixels");
}

// Each hybrid method takes the settings it reads: the reveal's belong to the paper's hybrid,
// the shutter rays' to hybrid-rays; one given to the other is a one-line usage error.
TEST(CliTest, EachHybridMethodTakesItsOwnSettings) {
  const fs::path dir = tempDir("hybrid-methods");
  const std::string out = " --width 32 --height 18 --out " + (dir / "hybrid.png").string();
  const CliRun paper = hmblur("render --scene living-room --method hybrid --edge-threshold 0.5 --reveal-stop luminance" + out);
  ASSERT_EQ(paper.exitCode, 0) << paper.output;
  EXPECT_EQ(paper.output.find("warning"), std::string::npos) << paper.output;
  const CliRun rays = hmblur("render --scene living-room --method hybrid-rays --shutter-rays 4 --ray-budget 100" + out);
  ASSERT_EQ(rays.exitCode, 0) << rays.output;
  EXPECT_EQ(rays.output.find("warning"), std::string::npos) << rays.output;
  for (const auto& [args, needle] : std::vector<std::pair<std::string, std::string>>{
           {"--method hybrid-rays --edge-threshold 0.5", "--edge-threshold is a setting of --method hybrid, not of --method hybrid-rays"},
           {"--method hybrid --shutter-rays 8", "--shutter-rays is a setting of --method hybrid-rays, not of --method hybrid"},
           {"--method hybrid --ray-budget 8", "--ray-budget is a setting of --method hybrid-rays"},
           {"--method hybrid-rays --shutter-rays 0", "--method hybrid"},
           {"--method hybrid-rays --shutter-rays 3", "shutter-rays must be 2, 4, 8 or 16"}}) {
    const CliRun run = hmblur("--quiet render --scene living-room" + out + " " + args);
    EXPECT_NE(run.exitCode, 0) << args;
    expectOneLineError(run, needle);
  }
}

TEST(CliTest, HybridSettingsAndCountsReachTheReportAndBadOnesFailInOneLine) {
  const fs::path dir = tempDir("hybrid");
  const CliRun run = hmblur("--quiet render --scene living-room --method hybrid --edge-threshold 0.5 "
                            "--reveal-stop luminance --max-recursion 3 --composite weights --width 64 --height 36 "
                            "--out " + (dir / "hybrid.exr").string() + " --report " + (dir / "report.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  nlohmann::json report;
  std::ifstream(dir / "report.json") >> report;
  const auto& settings = report["settings"];
  EXPECT_FLOAT_EQ(settings["edge_threshold"].get<float>(), 0.5f);
  EXPECT_EQ(settings["reveal_stop"], "luminance");
  EXPECT_EQ(settings["max_recursion"], 3);
  EXPECT_EQ(settings["composite"], "weights");
  // The vase moves across the sofa: some pixels are masked, and each traces at least one ray.
  EXPECT_GT(settings["mask_pixels"].get<uint64_t>(), 0u);
  EXPECT_GE(settings["reveal_rays"].get<uint64_t>(), settings["mask_pixels"].get<uint64_t>());
  const io::LayeredImage image = io::readExr((dir / "hybrid.exr").string());
  std::vector<std::string> names;
  for (const auto& layer : image.layers) names.push_back(layer.name);
  for (const char* layer : {"rayMask", "revealed", "revealedDepth", "revealedObjectId"})
    EXPECT_NE(std::find(names.begin(), names.end(), layer), names.end()) << layer;
  expectOneLineError(hmblur("--quiet render --method hybrid --composite magic --width 8 --height 8"), "magic");
  expectOneLineError(hmblur("--quiet render --method hybrid --edge-threshold 1.5 --width 8 --height 8"),
                     "edge-threshold must be");
  expectOneLineError(hmblur("--quiet render --method hybrid --max-recursion 0 --width 8 --height 8"), "recursion");
  expectOneLineError(hmblur("--quiet render --method hybrid --filter jimenez --width 8 --height 8"),
                     "--filter is a setting of --method postprocess");
  expectOneLineError(hmblur("--quiet render --method hybrid --range centered --width 8 --height 8"), "adapted");
  expectOneLineError(hmblur("--quiet render --method hybrid --composite weights --motion-path curved --width 8 "
                            "--height 8"),
                     "weights composite follows straight paths");
}

// What the loader leaves out reaches the terminal once per warning; --quiet silences it and
// --strict refuses the scene.
TEST(CliTest, LoaderWarningsReachStderrAndStrictRefusesThem) {
  const fs::path dir = tempDir("warnings");
  scene::test::GltfWriter w;
  nlohmann::json quad = scene::test::addQuadPrimitive(w);
  nlohmann::json points = quad;
  points["mode"] = 0;
  w.doc["extensionsUsed"] = {"KHR_materials_clearcoat"};
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({quad, points})}}), w.addNode({{"mesh", 0}})});
  const std::string scene = w.writeGltf(dir / "warned.gltf").string();
  const std::string args = "render --scene " + scene + " --width 8 --height 8 --out " + (dir / "f.png").string();

  const CliRun run = hmblur(args);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const auto count = [&](const std::string& text) {
    size_t n = 0;
    for (size_t at = run.output.find(text); at != std::string::npos; at = run.output.find(text, at + 1)) ++n;
    return n;
  };
  // The points primitive is one warning, used twice (the scene's stillness is said apart).
  EXPECT_EQ(count("hmblur: warning: " + scene + ": "), 2u) << run.output;
  EXPECT_EQ(count("hmblur: warning: nothing moves on screen"), 1u) << run.output;
  EXPECT_EQ(count("KHR_materials_clearcoat is not implemented"), 1u) << run.output;
  EXPECT_EQ(count("points skipped"), 1u) << run.output;

  const CliRun quiet = hmblur("--quiet " + args);
  ASSERT_EQ(quiet.exitCode, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("warning"), std::string::npos) << quiet.output;

  expectOneLineError(hmblur("--quiet --strict " + args), "(--strict; 2 warning(s) in all)");
}

TEST(CliTest, VersionAndUsageErrorsExitTwo) {
  const CliRun version = hmblur("--version");
  EXPECT_EQ(version.exitCode, 0);
  EXPECT_EQ(version.output.rfind("hmblur ", 0), 0u) << version.output;
  EXPECT_EQ(hmblur("render --no-such-flag").exitCode, 2);
  EXPECT_EQ(hmblur("render --width abc").exitCode, 2);
  EXPECT_EQ(hmblur("no-such-command").exitCode, 2);
  for (const auto& [args, needle] : std::vector<std::pair<std::string, std::string>>{
           {"--method magic", "unknown method"},
           {"--method sharp --spp 4", "--spp is a setting of --method reference, not of --method sharp"},
           {"--method postprocess --edge-threshold 0.5", "--method hybrid"},
           {"--method sharp --time-slices 2",
            "--time-slices is a setting of --method postprocess or hybrid or hybrid-rays"},
           {"--method hybrid --time-slices 0", "time-slices"},
           {"--method test-pattern --repeat 0", "--repeat"},
           {"--method test-pattern --fps 0", "fps"},
           {"--method test-pattern --exposure 0.01 --shutter-angle 90", "not both"},
           {"--method test-pattern --frames 5", "FIRST:LAST"},
           {"--method test-pattern --frames 1:2 --repeat 3", "--repeat times one frame"},
           {"--method test-pattern --frames 1:2 --frame-time 0.5", "exclude each other"}}) {
    const CliRun run = hmblur("--quiet render " + args);
    EXPECT_EQ(run.exitCode, 2) << args << ": " << run.output;
    expectOneLineError(run, needle);
  }
}

// --fps, --exposure and --shutter-angle replace the scene's shutter, in the image and the report.
TEST(CliTest, ShutterChoicesReachTheImageAndTheReport) {
  const fs::path dir = tempDir("shutter");
  const auto render = [&](const std::string& name, const std::string& shutter) {
    const CliRun run = hmblur("--quiet render --scene temple --method postprocess --width 48 --height 27 " + shutter +
                              " --out " + (dir / (name + ".png")).string() + " --report " +
                              (dir / (name + ".json")).string());
    EXPECT_EQ(run.exitCode, 0) << run.output;
    nlohmann::json report;
    std::ifstream(dir / (name + ".json")) >> report;
    return report;
  };
  const nlohmann::json scenes = render("scenes", "");
  const nlohmann::json chosen = render("chosen", "--fps 30 --exposure 0.004");
  EXPECT_FLOAT_EQ(chosen["scene"]["settings"]["fps"].get<float>(), 30.0f);
  EXPECT_FLOAT_EQ(chosen["scene"]["settings"]["exposure_s"].get<float>(), 0.004f);
  EXPECT_NE(scenes["scene"]["settings"]["exposure_s"], chosen["scene"]["settings"]["exposure_s"]);
  const nlohmann::json angle = render("angle", "--fps 60 --shutter-angle 180");
  EXPECT_FLOAT_EQ(angle["scene"]["settings"]["exposure_s"].get<float>(), 1.0f / 120.0f);
  EXPECT_FLOAT_EQ(angle["scene"]["settings"]["shutter_angle_deg"].get<float>(), 180.0f);
  EXPECT_NE(io::readPng(dir / "scenes.png").pixels, io::readPng(dir / "chosen.png").pixels);

  // A glTF file, which has no shutter of its own, plays at 24 fps under a 180-degree shutter.
  scene::test::GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({scene::test::addQuadPrimitive(w)})}})});
  const std::string file = w.writeGltf(dir / "quad.gltf").string();
  const CliRun quad = hmblur("--quiet render --scene " + file + " --width 8 --height 8 --out " +
                             (dir / "quad.png").string() + " --report " + (dir / "quad.json").string());
  ASSERT_EQ(quad.exitCode, 0) << quad.output;
  nlohmann::json report;
  std::ifstream(dir / "quad.json") >> report;
  EXPECT_FLOAT_EQ(report["scene"]["settings"]["fps"].get<float>(), 24.0f) << report["scene"].dump();
  EXPECT_FLOAT_EQ(report["scene"]["settings"]["shutter_angle_deg"].get<float>(), 180.0f) << report["scene"].dump();
}

// `render` times a frame after an untimed first one (kernels compile on first use); --repeat
// times it several times. The report keeps both, labelled.
TEST(CliTest, RenderTimesWarmFramesAndReportsTheColdOneApart) {
  const fs::path dir = tempDir("timing");
  const CliRun run = hmblur("render --scene temple --method sharp --width 32 --height 18 --repeat 3 --out " +
                            (dir / "f.png").string() + " --report " + (dir / "r.json").string());
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("(median of 3, "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("first frame "), std::string::npos) << run.output;
  nlohmann::json report;
  std::ifstream(dir / "r.json") >> report;
  EXPECT_EQ(report["timing"]["frames_ms"].size(), 3u);
  EXPECT_TRUE(report["timing"]["median_ms"].is_number());
  EXPECT_TRUE(report["timing"]["cold_ms"].is_number());
  EXPECT_LE(report["timing"]["min_ms"].get<double>(), report["timing"]["median_ms"].get<double>());
}

TEST(CliTest, HelpListsTheSubcommands) {
  const CliRun run = hmblur("--help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* sub : {"render", "demo", "list-scenes", "list-devices"})
    EXPECT_NE(run.output.find(sub), std::string::npos) << sub;
}

}  // namespace
}  // namespace hmb::test
