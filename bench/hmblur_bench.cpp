// hmblur-bench: the benchmark driver, one subcommand per suite. Device time comes from
// timestamp queries; each suite warms up, repeats, and reports medians and spread, with the
// device, driver, CPU, LP_NUM_THREADS and git revision (bench/README.md). Errors are one line
// on stderr and a non-zero exit.
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"
#include "runtime/error.h"
#include "runtime/report.h"
#include "runtime/system_info.h"
#include "runtime/vulkan/context.h"
#include "scenes/reference_scenes.h"

namespace fs = std::filesystem;

namespace {

enum ExitCode { kOk = 0, kError = 1 };

struct GlobalOptions {
  bool quiet = false;
  int device = -1;
};

struct RasterOptions {
  std::string out = "bench/results/raster-vs-graphics.json";
  std::vector<std::string> sizes = {"640x360", "1280x720", "1920x1080"};
  std::vector<std::string> scenes = hmb::scene::referenceSceneNames();
  int warmup = 3;
  int repeats = 15;
};

// The command as typed, for the report (arguments with spaces quoted).
std::string commandLine(int argc, char** argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) {
    std::string arg = argv[i];
    if (i == 0) arg = fs::path(arg).filename().string();  // no machine-specific path in reports
    if (arg.find_first_of(" \t\"'") != std::string::npos) arg = "'" + arg + "'";
    line += (i ? " " : "") + arg;
  }
  return line;
}

int raster(const GlobalOptions& global, const RasterOptions& options, const std::string& command) {
  hmb::bench::RasterSuiteOptions suite;
  suite.scenes = options.scenes;
  for (const std::string& size : options.sizes) suite.sizes.push_back(hmb::bench::parseImageSize(size));
  suite.warmup = options.warmup;
  suite.repeats = options.repeats;
  const fs::path parent = fs::path(options.out).parent_path();
  if (!options.out.empty() && !parent.empty() && !fs::is_directory(parent))
    throw hmb::Error("--out '" + options.out + "': directory '" + parent.string() + "' does not exist");

  hmb::vk::ContextOptions contextOptions;
  contextOptions.deviceIndex = global.device;
  const hmb::vk::Context context(contextOptions);
  // The graphics pipeline gets its own logical device on the same physical device, so that
  // its render passes cannot disturb the compute queue's timestamps (bench/raster_suite.h).
  contextOptions.deviceIndex = static_cast<int>(context.info().index);
  const hmb::vk::Context graphicsContext(contextOptions);
  const auto progress = [&](const std::string& message) {
    if (!global.quiet) std::cerr << "hmblur-bench: " << message << '\n';
  };
  progress("device: " + context.info().name);
  const std::vector<hmb::bench::RasterCase> cases =
      hmb::bench::runRasterSuite(context, graphicsContext, suite, progress);

  hmb::bench::printRasterTable(std::cout, cases);
  for (const auto& c : cases)
    if (!(c.passCoverage.median >= hmb::bench::kMinPassCoverage))  // also catches NaN
      std::cerr << "hmblur-bench: warning: " << c.scene << " " << c.size.width << "x" << c.size.height
                << ": pass timestamps cover only " << int(100.0 * c.passCoverage.median)
                << "% of the frame; per-pass times are suspect\n";
  for (const auto& c : cases)
    if (c.otherCpuLoad > hmb::bench::kMaxOtherCpuLoad)
      std::cerr << "hmblur-bench: warning: " << c.scene << " " << c.size.width << "x" << c.size.height
                << ": other processes kept " << c.otherCpuLoad << " cores busy; its times are disturbed\n";
  if (options.out.empty()) return kOk;
  nlohmann::json report = {
      {"suite", "raster"},
      {"what", "compute rasterizer (G-buffer stage) vs the device's graphics pipeline on the same clip-space "
               "triangles"},
      {"note", "compute_visibility sums the rasterizer's passes (clears through rasterize) and excludes "
               "transform_vertices: the graphics pipeline is handed already-transformed clip-space vertices. "
               "graphics_draw is its render pass (clear, draws, store). Ratios are paired per iteration. The "
               "graphics pipeline runs on a second logical device of the same physical device: on lavapipe a "
               "render pass on the compute queue would defer that queue's later timestamps."},
      {"command", command},
      {"date", hmb::utcTimestamp()},
      {"device", hmb::deviceJson(context.info())},
      {"system", hmb::systemJson(hmb::querySystemInfo())},
      {"settings",
       {{"warmup", suite.warmup},
        {"repeats", suite.repeats},
        {"sizes", options.sizes},
        {"scenes", options.scenes},
        {"min_id_agreement", hmb::bench::kMinIdAgreement}}},
      {"cases", nlohmann::json::array()},
  };
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::rasterCaseJson(c));
  hmb::writeJson(options.out, report);
  progress("wrote " + options.out);
  return kOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hmblur-bench: benchmark suites for hybrid-mblur (device time from Vulkan timestamps)"};
  app.require_subcommand(1);
  app.fallthrough();
  GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "No progress on stderr (the table and errors still print)");
  app.add_option("--device", global.device, "Vulkan device index (hmblur list-devices); default: best compute device")
      ->check(CLI::NonNegativeNumber);

  RasterOptions rasterOptions;
  CLI::App* rasterCmd =
      app.add_subcommand("raster", "Compute rasterizer vs the device's own graphics pipeline, same triangles");
  rasterCmd->add_option("--out", rasterOptions.out, "JSON results file (empty: none)")->capture_default_str();
  rasterCmd->add_option("--sizes", rasterOptions.sizes, "Image sizes, WIDTHxHEIGHT, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  rasterCmd->add_option("--scenes", rasterOptions.scenes, "Reference scene names or glTF files, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  rasterCmd->add_option("--warmup", rasterOptions.warmup, "Untimed iterations per case")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  rasterCmd->add_option("--repeats", rasterOptions.repeats, "Timed iterations per case")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }

  try {
    if (*rasterCmd) return raster(global, rasterOptions, commandLine(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "hmblur-bench: error: " << e.what() << '\n';
    return kError;
  }
  return kOk;
}
