// hmblur-bench: the benchmark driver, one subcommand per suite. Device time comes from
// timestamp queries; each suite warms up, repeats, and reports medians and spread, with the
// device, driver, CPU, LP_NUM_THREADS and git revision (bench/README.md). Errors are one line
// on stderr and a non-zero exit. `--suite NAME` is another spelling of the subcommand NAME.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench/bench_scenes.h"
#include "bench/bvh_suite.h"
#include "bench/driver_files.h"
#include "bench/embree_reference.h"
#include "bench/engine_suite.h"
#include "bench/error_time_suite.h"
#include "bench/explain_suite.h"
#include "bench/kernels_suite.h"
#include "bench/passes_suite.h"
#include "bench/raster_suite.h"
#include "bench/side_by_side.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/post_process_settings.h"
#include "hmblur/report.h"
#include "hmblur/system_info.h"
#include "kernels/mblur/mblur_layout.h"
#include "scenes/reference_scenes.h"

namespace fs = std::filesystem;

namespace {

enum ExitCode { kOk = 0, kError = 1, kValidationFailed = 3 };

struct GlobalOptions {
  bool quiet = false;
  int device = -1;
  bool validation = false;
  bool bindByAddress = false;
  std::string deviceProfile;  // auto, cpu or gpu; empty: HMB_DEVICE_PROFILE, else auto
  std::string driverFiles;  // run on this unpacked driver (driver_files.h)
};

struct RasterOptions {
  std::string out = "out/bench/raster-vs-graphics.json";
  std::vector<std::string> sizes = {"640x360", "1280x720", "1920x1080"};
  std::vector<std::string> scenes = hmb::scene::referenceSceneNames();
  int warmup = 3;
  int repeats = 15;
};

struct BvhOptions {
  std::string out = "out/bench/bvh-vs-embree.json";
  std::vector<std::string> scenes = [] {
    std::vector<std::string> names = hmb::scene::referenceSceneNames();
    names.push_back(hmb::bench::kCubeSphere1m);
    names.push_back(hmb::bench::kCadEngine);
    return names;
  }();
  int warmup = 1;
  int repeats = 3;
  int embreeThreads = 0;
  bool rayQuery = true;  // the driver's own ray queries beside ours, where it has them
};

struct ErrorTimeOptions {
  std::string out = "out/bench/error-vs-time/error-vs-time.json";
  std::vector<std::string> scenes = hmb::scene::referenceSceneNames();
  std::string size = "1280x720";
  std::string referenceDir;
  uint32_t judgeSpp = 1024;
  std::vector<uint32_t> referenceSpp = {1, 2, 4, 8, 16, 32, 64, 128, 256};
  std::vector<double> rayBudgets = hmb::bench::ErrorTimeSuiteOptions{}.rayBudgets;
  uint32_t frontSpp = hmb::bench::ErrorTimeSuiteOptions{}.frontSpp;
  int warmup = 1;
  int repeats = 3;
  int referenceRepeats = 1;
};

struct PassesOptions {
  std::string out = "out/bench/passes/passes.json";
  std::vector<std::string> scenes = hmb::scene::referenceSceneNames();
  std::vector<std::string> sizes = {"640x360", "1280x720", "1920x1080"};
  std::vector<std::string> methods = {"sharp", "postprocess", "hybrid", "hybrid-rays"};
  int warmup = 1;
  int repeats = 3;
};

struct EngineOptions {
  std::string out = "out/bench/engine/engine.json";
  std::vector<std::string> scenes = hmb::scene::referenceSceneNames();
  std::vector<std::string> sizes = {"1280x720"};
  int warmup = 2;
  int repeats = 9;
};

struct ExplainOptions {
  std::string out = "out/bench/error-explanation/explanation.json";
  std::vector<std::string> scenes = hmb::scene::referenceSceneNames();
  std::string size = "320x180";
  uint32_t referenceSpp = 256;
  std::vector<std::string> methods = {"postprocess", "hybrid", "hybrid-rays"};
  uint32_t timeSlices = 1;
  std::optional<uint32_t> tileSize;
};

struct KernelsOptions {
  std::string out = "out/bench/kernels/kernels.json";
  hmb::bench::KernelsSuiteOptions suite;
  std::vector<std::string> sizes = [] {
    std::vector<std::string> names;
    for (const hmb::bench::ImageSize& size : hmb::bench::KernelsSuiteOptions().sizes)
      names.push_back(hmb::bench::sizeName(size));
    return names;
  }();
  std::vector<std::string> drivers;  // several: side by side (side_by_side.h)
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

// Before any work: --out's folder is made if missing, and refused if it cannot be. Results go
// under out/bench/ unless --out says otherwise: the committed ones in bench/results/ change
// only when a command names them.
void checkOutputDirectory(const std::string& out) {
  const fs::path parent = fs::path(out).parent_path();
  if (out.empty() || parent.empty()) return;
  std::error_code error;
  fs::create_directories(parent, error);
  if (!fs::is_directory(parent))
    throw hmb::Error("--out '" + out + "': cannot create the folder '" + parent.string() + "'");
}

// Progress lines on stderr unless --quiet.
std::function<void(const std::string&)> progressPrinter(const GlobalOptions& global) {
  return [quiet = global.quiet](const std::string& message) {
    if (!quiet) std::cerr << "hmblur-bench: " << message << '\n';
  };
}

// The report header's first sentence: device, driver, CPU, threads and revision.
std::string machineLine(const hmb::vk::Context& context, const hmb::SystemInfo& system) {
  std::ostringstream line;
  line << "Device " << context.info().name << " (" << context.info().driverInfo << "), CPU " << system.cpu << ", "
       << system.hardwareThreads << " hardware threads, LP_NUM_THREADS " << system.lpNumThreads << ", revision "
       << system.gitRevision << ".";
  return line.str();
}

// The fields every suite's JSON report starts with: the suite, what it measures, the command,
// the date, and the device and machine it ran on.
nlohmann::json reportHead(const std::string& suite, const std::string& what, const std::string& command,
                          const hmb::vk::Context& context, const hmb::SystemInfo& system) {
  return {{"suite", suite},
          {"what", what},
          {"command", command},
          {"date", hmb::utcTimestamp()},
          {"device", hmb::deviceJson(context)},
          {"system", hmb::systemJson(system)}};
}

// The options of the device --device names (default: the preferred one).
hmb::vk::ContextOptions contextOptions(const GlobalOptions& global) {
  hmb::vk::ContextOptions options;
  options.deviceIndex = global.device;
  options.validation = global.validation;
  options.bindByAddress = global.bindByAddress;
  options.deviceProfile = hmb::vk::deviceProfileChoiceOrEnvironment(global.deviceProfile);
  return options;
}

hmb::vk::Context openContext(const GlobalOptions& global) { return hmb::vk::Context(contextOptions(global)); }

// With --validation, any validation error fails the suite after its work is done.
int validationVerdict(std::initializer_list<const hmb::vk::Context*> contexts) {
  int verdict = kOk;
  for (const hmb::vk::Context* context : contexts) {
    if (!context->validationEnabled() || context->validationErrors() == 0) continue;
    std::cerr << "hmblur-bench: error: " << context->validationErrors() << " Vulkan validation error(s)\n";
    for (const std::string& message : context->validationMessages()) std::cerr << "  " << message << '\n';
    verdict = kValidationFailed;
  }
  return verdict;
}

// Writes the CSV and Markdown files beside the JSON file `out` (same stem).
void writeBeside(const std::string& out, const std::function<void(std::ostream&)>& csv,
                 const std::function<void(std::ostream&)>& markdown) {
  const fs::path stem = fs::path(out).replace_extension();
  std::ofstream csvFile(stem.string() + ".csv"), markdownFile(stem.string() + ".md");
  csv(csvFile);
  markdown(markdownFile);
  if (!csvFile || !markdownFile) throw hmb::Error("could not write " + stem.string() + ".csv / .md");
}

int raster(const GlobalOptions& global, const RasterOptions& options, const std::string& command) {
  hmb::bench::RasterSuiteOptions suite;
  suite.scenes = options.scenes;
  for (const std::string& size : options.sizes) suite.sizes.push_back(hmb::bench::parseImageSize(size));
  suite.warmup = options.warmup;
  suite.repeats = options.repeats;
  checkOutputDirectory(options.out);

  hmb::vk::ContextOptions deviceOptions = contextOptions(global);
  const hmb::vk::Context context(deviceOptions);
  // The graphics pipeline gets its own logical device on the same physical device, so that
  // its render passes cannot disturb the compute queue's timestamps (bench/raster_suite.h).
  deviceOptions.deviceIndex = static_cast<int>(context.info().index);
  const hmb::vk::Context graphicsContext(deviceOptions);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const std::vector<hmb::bench::RasterCase> cases =
      hmb::bench::runRasterSuite(context, graphicsContext, suite, progress);

  hmb::bench::printRasterTable(std::cout, cases);
  for (const auto& c : cases)
    if (c.otherCpuLoad > hmb::bench::kMaxOtherCpuLoad)
      std::cerr << "hmblur-bench: warning: " << c.scene << " " << c.size.width << "x" << c.size.height
                << ": other processes kept " << c.otherCpuLoad << " cores busy; its times are disturbed\n";
  if (options.out.empty()) return validationVerdict({&context, &graphicsContext});
  nlohmann::json report =
      reportHead("raster",
                 "compute rasterizer (G-buffer stage) vs the device's graphics pipeline on the same clip-space "
                 "triangles",
                 command, context, hmb::querySystemInfo());
  report["note"] =
      "compute_visibility sums the rasterizer's passes (clears through rasterize) and excludes "
      "transform_vertices: the graphics pipeline is handed already-transformed clip-space vertices. "
      "graphics_draw is its render pass (clear, draws, store). Ratios are paired per iteration. The "
      "graphics pipeline runs on a second logical device of the same physical device: on lavapipe a "
      "render pass on the compute queue would defer that queue's later timestamps.";
  report["settings"] = {{"warmup", suite.warmup},
                        {"repeats", suite.repeats},
                        {"sizes", options.sizes},
                        {"scenes", options.scenes},
                        {"min_id_agreement", hmb::bench::kMinIdAgreement}};
  report["cases"] = nlohmann::json::array();
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::rasterCaseJson(c));
  hmb::writeJson(options.out, report);
  progress("wrote " + options.out);
  return validationVerdict({&context, &graphicsContext});
}

int bvh(const GlobalOptions& global, const BvhOptions& options, const std::string& command) {
  hmb::bench::BvhSuiteOptions suite;
  suite.scenes = options.scenes;
  // The CAD asset is a Debian package's: without it the default run goes on and says so.
  if (!hmb::bench::cadEnginePath() && options.scenes == BvhOptions{}.scenes) {
    std::erase(suite.scenes, std::string(hmb::bench::kCadEngine));
    std::cerr << "hmblur-bench: " << hmb::bench::kCadEngine << " left out: Debian's assimp-testmodels is not installed\n";
  }
  suite.warmup = options.warmup;
  suite.repeats = options.repeats;
  suite.embreeThreads = options.embreeThreads;
  suite.rayQueryAnchor = options.rayQuery;
  checkOutputDirectory(options.out);
  const hmb::vk::Context context = openContext(global);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const std::vector<hmb::bench::BvhCase> cases = hmb::bench::runBvhSuite(context, suite, progress);
  hmb::bench::printBvhTable(std::cout, cases);
  if (options.out.empty()) return validationVerdict({&context});
  nlohmann::json report =
      reportHead("bvh",
                 "device BVH build (binned SAH, compute) and trace kernel vs the CPU full-sweep SAH build and Embree, "
                 "same world-space triangles and rays",
                 command, context, hmb::querySystemInfo());
  report["note"] =
      "device times are Vulkan timestamps (build: triangle boxes + every level; trace: the trace-rays pass). "
      "Embree: rtcCommitScene (default quality) for build speed, rtcBuildBVH into our node layout for its SAH "
      "cost, rtcIntersect over embree_threads threads for rays. SAH costs: traversal 1, intersection 1, "
      "leaves of at most 4, normalized by the root's area. ray_query: the driver's own acceleration-structure build "
      "(bottom and top level, timestamps around both) and ray queries from a compute kernel, on a second logical "
      "device of the same physical device, checked against Embree like the device.";
  report["embree"] = hmb::bench::embreeAvailable() ? hmb::bench::embreeVersion() : "unavailable";
  report["settings"] = {{"warmup", suite.warmup},
                        {"repeats", suite.repeats},
                        {"embree_threads", hmb::bench::embreeThreadCount(suite.embreeThreads)},
                        {"ray_query", hmb::bench::rayQueryAnchorSkipped(context, suite).empty()
                                          ? "measured: the driver's own acceleration structures (bottom level "
                                            "prefer-fast-trace, opaque; one identity instance) and ray queries"
                                          : "left out: " + hmb::bench::rayQueryAnchorSkipped(context, suite)},
                        {"coherent_rays", "one per pixel, 640x360, from the scene camera"},
                        {"incoherent_rays", suite.incoherentRays},
                        {"min_hit_agreement", hmb::bench::kMinHitAgreement}};
  report["cases"] = nlohmann::json::array();
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::bvhCaseJson(c));
  hmb::writeJson(options.out, report);
  progress("wrote " + options.out);
  return validationVerdict({&context});
}

int errorTime(const GlobalOptions& global, const ErrorTimeOptions& options, const std::string& command) {
  hmb::bench::ErrorTimeSuiteOptions suite;
  suite.scenes = options.scenes;
  suite.size = hmb::bench::parseImageSize(options.size);
  suite.referenceDir = options.referenceDir;
  suite.judgeSpp = options.judgeSpp;
  suite.referenceSpp = options.referenceSpp;
  suite.rayBudgets = options.rayBudgets;
  suite.frontSpp = options.frontSpp;
  suite.warmup = options.warmup;
  suite.repeats = options.repeats;
  suite.referenceRepeats = options.referenceRepeats;
  checkOutputDirectory(options.out);
  if (!suite.referenceDir.empty() && !fs::is_directory(suite.referenceDir))
    throw hmb::Error("--reference-dir '" + suite.referenceDir + "' is not a directory");
  hmb::vk::Context context = openContext(global);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const std::vector<hmb::bench::ErrorTimeScene> scenes = hmb::bench::runErrorTimeSuite(context, suite, progress);

  const hmb::SystemInfo system = hmb::querySystemInfo();
  std::ostringstream header;
  header << machineLine(context, system) << ' ' << suite.size.width << "x" << suite.size.height
         << "; median device time (timestamp queries) of " << suite.repeats << " renders after " << suite.warmup
         << " warm-up (reference: " << suite.referenceRepeats << ", no warm-up). Command: `" << command << "`";
  hmb::bench::writeErrorTimeMarkdown(std::cout, scenes, header.str());
  if (options.out.empty()) return validationVerdict({&context});
  nlohmann::json report =
      reportHead("error-vs-time",
                 "error (PSNR, SSIM; frame and blur region) against a high-spp judge, and median frame time, of every "
                 "method over a range of settings",
                 command, context, system);
  report["settings"] = {
      {"size", options.size},
      {"warmup", suite.warmup},
      {"repeats", suite.repeats},
      {"reference_repeats", suite.referenceRepeats},
      {"judge_spp", suite.referenceDir.empty() ? nlohmann::json(suite.judgeSpp) : nlohmann::json(nullptr)},
      {"reference_spp", suite.referenceSpp},
      {"ray_budgets_per_pixel", suite.rayBudgets},
      {"front_spp", suite.frontSpp}};
  report["scenes"] = nlohmann::json::array();
  for (const auto& s : scenes) report["scenes"].push_back(hmb::bench::errorTimeSceneJson(s));
  hmb::writeJson(options.out, report);
  writeBeside(
      options.out, [&](std::ostream& out) { hmb::bench::writeErrorTimeCsv(out, scenes); },
      [&](std::ostream& out) { hmb::bench::writeErrorTimeMarkdown(out, scenes, header.str()); });
  progress("wrote " + options.out + " and the .csv and .md beside it");
  return validationVerdict({&context});
}

int passes(const GlobalOptions& global, const PassesOptions& options, const std::string& command) {
  hmb::bench::PassesSuiteOptions suite;
  suite.scenes = options.scenes;
  suite.sizes.clear();
  for (const std::string& size : options.sizes) suite.sizes.push_back(hmb::bench::parseImageSize(size));
  suite.methods = options.methods;
  suite.warmup = options.warmup;
  suite.repeats = options.repeats;
  checkOutputDirectory(options.out);
  hmb::vk::Context context = openContext(global);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const std::vector<hmb::bench::PassesCase> cases = hmb::bench::runPassesSuite(context, suite, progress);

  const hmb::SystemInfo system = hmb::querySystemInfo();
  std::ostringstream header;
  header << machineLine(context, system) << " Median device time (timestamp queries) of " << suite.repeats
         << " renders after " << suite.warmup << " warm-up, the methods of a scene and size rendered in turn, a "
         << "round at a time; x post-process is the median over the rounds of a frame over post-process's of the "
         << "same round. The hybrid's mesh trees are scene setup, listed but not in its frame. Peak device memory: the most the renderer's buffers held at once during a render. "
         << "Command: `" << command << "`";
  hmb::bench::writePassesMarkdown(std::cout, cases, header.str());
  if (options.out.empty()) return validationVerdict({&context});
  nlohmann::json report =
      reportHead("passes", "per-pass device time of each method, scene and image size, and each render's device memory",
                 command, context, system);
  report["settings"] = {
      {"sizes", options.sizes}, {"methods", options.methods}, {"warmup", suite.warmup}, {"repeats", suite.repeats}};
  report["cases"] = nlohmann::json::array();
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::passesCaseJson(c));
  hmb::writeJson(options.out, report);
  writeBeside(
      options.out, [&](std::ostream& out) { hmb::bench::writePassesCsv(out, cases); },
      [&](std::ostream& out) { hmb::bench::writePassesMarkdown(out, cases, header.str()); });
  progress("wrote " + options.out + " and the .csv and .md beside it");
  return validationVerdict({&context});
}

int engine(const GlobalOptions& global, const EngineOptions& options, const std::string& command) {
  hmb::bench::EngineSuiteOptions suite;
  suite.scenes = options.scenes;
  suite.sizes.clear();
  for (const std::string& size : options.sizes) suite.sizes.push_back(hmb::bench::parseImageSize(size));
  suite.warmup = options.warmup;
  suite.repeats = options.repeats;
  checkOutputDirectory(options.out);
  hmb::vk::Context context = openContext(global);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const std::vector<hmb::bench::EngineCase> cases = hmb::bench::runEngineSuite(context, suite, progress);

  const hmb::SystemInfo system = hmb::querySystemInfo();
  std::ostringstream header;
  header << machineLine(context, system) << " Median device time (timestamp queries) of " << suite.repeats
         << " frames of each path after " << suite.warmup << " warm-up, the two paths alternated. Command: `"
         << command << "`";
  hmb::bench::writeEngineMarkdown(std::cout, cases, header.str());
  if (options.out.empty()) return validationVerdict({&context});
  nlohmann::json report = reportHead(
      "engine", "the engine backend's post-process frame from an engine's G-buffer beside the command line's", command,
      context, system);
  report["settings"] = {{"sizes", options.sizes}, {"warmup", suite.warmup}, {"repeats", suite.repeats}};
  report["cases"] = nlohmann::json::array();
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::engineCaseJson(c));
  hmb::writeJson(options.out, report);
  writeBeside(
      options.out, [&](std::ostream& out) { hmb::bench::writeEngineCsv(out, cases); },
      [&](std::ostream& out) { hmb::bench::writeEngineMarkdown(out, cases, header.str()); });
  progress("wrote " + options.out + " and the .csv and .md beside it");
  return validationVerdict({&context});
}

int explain(const GlobalOptions& global, const ExplainOptions& options, const std::string& command) {
  hmb::bench::ExplainSuiteOptions suite;
  suite.scenes = options.scenes;
  suite.size = hmb::bench::parseImageSize(options.size);
  suite.referenceSpp = options.referenceSpp;
  suite.methods = options.methods;
  suite.timeSlices = options.timeSlices;
  suite.tileSize = options.tileSize;
  checkOutputDirectory(options.out);
  if (!options.out.empty()) {
    const fs::path folder = fs::path(options.out).parent_path();
    suite.imageDir = folder.empty() ? "." : folder.string();
  }
  hmb::vk::Context context = openContext(global);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const std::vector<hmb::bench::ExplainCase> cases = hmb::bench::runExplainSuite(context, suite, progress);

  const hmb::SystemInfo system = hmb::querySystemInfo();
  std::ostringstream header;
  header << machineLine(context, system) << ' ' << options.size << ", the reference " << suite.referenceSpp
         << " spp (two halves, seeds 1 and 2); the methods with " << suite.timeSlices
         << " time slice(s), tiles of "
         << (suite.tileSize ? std::to_string(*suite.tileSize) + " px" : std::string("their default size"))
         << ". Command: `" << command << "`";
  hmb::bench::writeExplainMarkdown(std::cout, cases, header.str());
  if (options.out.empty()) return validationVerdict({&context});
  nlohmann::json report =
      reportHead("explain", "where each method's blur-region error against the reference comes from, by class",
                 command, context, system);
  report["settings"] = {{"size", options.size},
                        {"reference_spp", suite.referenceSpp},
                        {"methods", options.methods},
                        {"time_slices", suite.timeSlices},
                        {"tile_size", suite.tileSize ? nlohmann::json(*suite.tileSize) : nlohmann::json(nullptr)}};
  report["cases"] = nlohmann::json::array();
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::explainCaseJson(c));
  hmb::writeJson(options.out, report);
  std::ofstream markdown(fs::path(options.out).replace_extension(".md"));
  hmb::bench::writeExplainMarkdown(markdown, cases, header.str());
  if (!markdown) throw hmb::Error("could not write the .md beside " + options.out);
  progress("wrote " + options.out + ", the .md beside it and a strip per scene and method");
  return validationVerdict({&context});
}

std::string shellQuoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

template <typename T>
std::string commaList(const std::vector<T>& values) {
  std::ostringstream out;
  for (size_t i = 0; i < values.size(); ++i) out << (i ? "," : "") << values[i];
  return out.str();
}

// The kernels suite once per driver of --drivers, each in a program of its own and one after
// the other, merged side by side (side_by_side.h).
int kernelsOnDrivers(const GlobalOptions& global, const KernelsOptions& options, const std::string& command) {
  if (!global.driverFiles.empty()) throw hmb::Error("--drivers and --driver-files: give one of the two");
  checkOutputDirectory(options.out);
  for (const std::string& driver : options.drivers)
    if (driver != "default") hmb::bench::resolveDriverFiles(driver);  // a bad path fails before any run
  const auto progress = progressPrinter(global);
  const fs::path scratch = fs::temp_directory_path() / ("hmblur-bench-drivers-" + std::to_string(getpid()));
  fs::create_directories(scratch);
  std::vector<hmb::bench::DriverReport> runs;
  int verdict = kOk;
  for (size_t d = 0; d < options.drivers.size(); ++d) {
    const std::string& driver = options.drivers[d];
    progress("driver " + std::to_string(d + 1) + " of " + std::to_string(options.drivers.size()) + ": " + driver);
    const fs::path out = scratch / ("driver-" + std::to_string(d) + ".json");
    std::string line = shellQuoted(fs::read_symlink("/proc/self/exe").string());
    if (global.quiet) line += " --quiet";
    if (global.device >= 0) line += " --device " + std::to_string(global.device);
    if (global.validation) line += " --validation";
    if (global.bindByAddress) line += " --bind-by-address";
    if (!global.deviceProfile.empty()) line += " --device-profile " + global.deviceProfile;
    if (driver != "default") line += " --driver-files " + shellQuoted(driver);
    line += " kernels --sizes " + commaList(options.sizes) + " --triangles " + commaList(options.suite.triangles) +
            " --rays " + commaList(options.suite.rays) + " --kernels " + commaList(options.suite.kernels) +
            " --warmup " + std::to_string(options.suite.warmup) + " --repeats " +
            std::to_string(options.suite.repeats) + " --out " + shellQuoted(out.string()) + " > /dev/null";
    const int status = std::system(line.c_str());
    const int exit = WIFEXITED(status) ? WEXITSTATUS(status) : kError;
    if (exit == kValidationFailed) verdict = kValidationFailed;
    else if (exit != kOk)
      throw hmb::Error("--drivers: the kernels suite on driver '" + driver + "' failed (exit " + std::to_string(exit) +
                       ")");
    std::ifstream in(out);
    runs.push_back({driver, nlohmann::json::parse(in)});
  }
  fs::remove_all(scratch);
  const nlohmann::json merged = hmb::bench::sideBySideJson(runs, command);
  hmb::bench::writeSideBySideMarkdown(std::cout, merged);
  if (options.out.empty()) return verdict;
  hmb::writeJson(options.out, merged);
  writeBeside(
      options.out, [&](std::ostream& out) { hmb::bench::writeSideBySideCsv(out, merged); },
      [&](std::ostream& out) { hmb::bench::writeSideBySideMarkdown(out, merged); });
  progress("wrote " + options.out + " and the .csv and .md beside it");
  return verdict;
}

int kernels(const GlobalOptions& global, const KernelsOptions& options, const std::string& command) {
  if (!options.drivers.empty()) return kernelsOnDrivers(global, options, command);
  hmb::bench::KernelsSuiteOptions suite = options.suite;
  suite.sizes.clear();
  for (const std::string& size : options.sizes) suite.sizes.push_back(hmb::bench::parseImageSize(size));
  checkOutputDirectory(options.out);
  const hmb::vk::Context context = openContext(global);
  const auto progress = progressPrinter(global);
  progress(hmb::deviceProgressLine(context));
  const hmb::bench::CpuSample cpuBefore = hmb::bench::sampleCpu();
  const std::vector<hmb::bench::KernelCase> cases = hmb::bench::runKernelsSuite(context, suite, progress);
  const double otherCpuLoad = hmb::bench::otherLoad(cpuBefore, hmb::bench::sampleCpu());

  const hmb::SystemInfo system = hmb::querySystemInfo();
  std::ostringstream header;
  header << machineLine(context, system) << " Median device time (timestamp queries) of " << suite.repeats
         << " runs after " << suite.warmup << " warm-up, each kernel alone on synthetic inputs drawn from seed "
         << hmb::bench::kKernelsSeed << "; other processes kept " << hmb::bench::fixed(otherCpuLoad, 2)
         << " cores busy over the run (per case: only those of a second or more). Command: `" << command << "`";
  hmb::bench::writeKernelsMarkdown(std::cout, cases, header.str());
  if (otherCpuLoad > hmb::bench::kMaxOtherCpuLoad)
    std::cerr << "hmblur-bench: warning: other processes kept " << otherCpuLoad
              << " cores busy during the run; its times are disturbed\n";
  for (const auto& c : cases)
    if (c.otherCpuLoad > hmb::bench::kMaxOtherCpuLoad)
      std::cerr << "hmblur-bench: warning: " << c.kernel << ": other processes kept " << c.otherCpuLoad
                << " cores busy; its times are disturbed\n";
  if (options.out.empty()) return validationVerdict({&context});
  nlohmann::json report =
      reportHead("kernels",
                 "device time and throughput of single kernels (raster, BVH build, trace, tile-max, gather) on "
                 "synthetic inputs of chosen sizes",
                 command, context, system);
  report["note"] =
      "raster: the rasterizer's visibility passes (clears through rasterize, summed) over random clip-space "
      "triangles, each vertex within raster_triangle_radius_pixels of a random centre, one double-sided instance. "
      "bvh-build: the builder's submissions (begin and every level; frame times summed) over the boxes of random "
      "triangles in the unit cube, each about N^-1/3 across, boxes uploaded from the host. trace: the trace-rays "
      "pass, rays from random points in the unit cube in random directions through the BVH over those triangles. "
      "tile-max and gather: one pass each over a G-buffer of random colours, depths and velocities (each component "
      "uniform in +-max_velocity_pixels), post-process defaults (m = 40, n = 3, 15 samples, adapted range). "
      "Throughput: items over the median time. other_cpu_load_cores: cores busy with other processes during the "
      "run, and during each case of a second or more (on a CPU device they compete with the kernels).";
  report["settings"] = {{"sizes", options.sizes},
                        {"triangles", suite.triangles},
                        {"rays", suite.rays},
                        {"kernels", suite.kernels},
                        {"warmup", suite.warmup},
                        {"repeats", suite.repeats},
                        {"seed", hmb::bench::kKernelsSeed},
                        {"raster_triangle_radius_pixels", hmb::bench::kRasterTriangleRadiusPixels},
                        {"max_velocity_pixels", hmb::bench::kMaxVelocityPixels}};
  report["other_cpu_load_cores"] = std::isnan(otherCpuLoad) ? nlohmann::json(nullptr) : nlohmann::json(otherCpuLoad);
  report["cases"] = nlohmann::json::array();
  for (const auto& c : cases) report["cases"].push_back(hmb::bench::kernelCaseJson(c));
  hmb::writeJson(options.out, report);
  writeBeside(
      options.out, [&](std::ostream& out) { hmb::bench::writeKernelsCsv(out, cases); },
      [&](std::ostream& out) { hmb::bench::writeKernelsMarkdown(out, cases, header.str()); });
  progress("wrote " + options.out + " and the .csv and .md beside it");
  return validationVerdict({&context});
}

// A comma-separated list of scenes.
void addScenesOption(CLI::App& command, std::vector<std::string>& scenes,
                     const std::string& what = "Reference scene names or glTF files") {
  command.add_option("--scenes,--scene", scenes, what + ", comma separated")->delimiter(',')->capture_default_str();
}

// The options before any suite's, on the whole command line and on the --suite pre-parse alike.
void addGlobalOptions(CLI::App& app, GlobalOptions& global) {
  app.add_flag("-q,--quiet", global.quiet, "No progress on stderr (the table and errors still print)");
  app.add_option("--device", global.device, "Vulkan device index (hmblur list-devices); default: best compute device")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--validation", global.validation,
               "Enable the Khronos validation layer; any validation error fails the suite (exit code 3)");
  app.add_flag("--bind-by-address", global.bindByAddress,
               "Kernels with an address build bind their groups of buffers as tables of device addresses "
               "(default: only where the device has too few storage-buffer bindings)");
  app.add_option("--device-profile", global.deviceProfile,
                 "Whose choices the passes make: auto (the device type's), cpu or gpu (forced); default: "
                 "HMB_DEVICE_PROFILE, else auto")
      ->check(CLI::IsMember({"auto", "cpu", "gpu"}));
  app.add_option("--driver-files", global.driverFiles,
                 "Run on the Vulkan driver of this ICD manifest or folder (e.g. the one "
                 "scripts/mesa25-lavapipe.sh unpacks), not the installed one");
}

// --out, --warmup and --repeats, which every suite has.
void addCommonOptions(CLI::App& command, std::string& out, int& warmup, int& repeats) {
  command.add_option("--out", out, "JSON results file (empty: none)")->capture_default_str();
  command.add_option("--warmup", warmup, "Untimed iterations per case")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  command.add_option("--repeats,--repeat", repeats, "Timed iterations per case")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hmblur-bench: benchmark suites for hybrid-mblur (device time from Vulkan timestamps)"};
  app.require_subcommand(1);
  app.fallthrough();
  GlobalOptions global;
  addGlobalOptions(app, global);
  std::string suiteName;
  app.add_option("--suite", suiteName, "The suite to run, as the subcommand of that name: --suite NAME [its options]");

  RasterOptions rasterOptions;
  CLI::App* rasterCmd =
      app.add_subcommand("raster", "Compute rasterizer vs the device's own graphics pipeline, same triangles");
  addCommonOptions(*rasterCmd, rasterOptions.out, rasterOptions.warmup, rasterOptions.repeats);
  rasterCmd->add_option("--sizes", rasterOptions.sizes, "Image sizes, WIDTHxHEIGHT, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  addScenesOption(*rasterCmd, rasterOptions.scenes);

  BvhOptions bvhOptions;
  CLI::App* bvhCmd = app.add_subcommand(
      "bvh", "Device BVH build and trace vs the CPU full-sweep SAH build and Embree, same triangles and rays");
  addCommonOptions(*bvhCmd, bvhOptions.out, bvhOptions.warmup, bvhOptions.repeats);
  addScenesOption(*bvhCmd, bvhOptions.scenes,
                  "Reference scenes, glTF files, " + std::string(hmb::bench::kCubeSphere1m) + " or " +
                      hmb::bench::kCadEngine);
  bvhCmd->add_option("--embree-threads", bvhOptions.embreeThreads,
                     "Embree's threads (0: LP_NUM_THREADS when set, else every hardware thread)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  bvhCmd->add_flag("!--no-ray-query", bvhOptions.rayQuery,
                   "Leave out the driver's own acceleration structures and ray queries (measured where the "
                   "device has VK_KHR_ray_query, e.g. Mesa >= 24.1 lavapipe)");

  ErrorTimeOptions errorTimeOptions;
  CLI::App* errorTimeCmd = app.add_subcommand(
      "error-vs-time", "Error against a high-spp judge and median frame time of every method over its settings");
  addCommonOptions(*errorTimeCmd, errorTimeOptions.out, errorTimeOptions.warmup, errorTimeOptions.repeats);
  addScenesOption(*errorTimeCmd, errorTimeOptions.scenes);
  errorTimeCmd->add_option("--size", errorTimeOptions.size, "Image size, WIDTHxHEIGHT")->capture_default_str();
  errorTimeCmd->add_option("--reference-dir", errorTimeOptions.referenceDir,
                           "Judges from DIR/SCENE-reference.exr (default: rendered here at --judge-spp)");
  errorTimeCmd->add_option("--judge-spp", errorTimeOptions.judgeSpp, "Samples per pixel of a judge rendered here")
      ->check(CLI::Range(1u, 65536u))
      ->capture_default_str();
  errorTimeCmd->add_option("--reference-spp", errorTimeOptions.referenceSpp, "The reference's spp series, comma separated")
      ->delimiter(',')
      ->check(CLI::Range(1u, 65536u))
      ->capture_default_str();
  errorTimeCmd->add_option("--reference-repeats", errorTimeOptions.referenceRepeats, "Timed renders per reference spp")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  errorTimeCmd
      ->add_option("--ray-budgets", errorTimeOptions.rayBudgets,
                   "hybrid-rays' ray budgets in rays per image pixel, comma separated")
      ->delimiter(',')
      ->check(CLI::Range(1e-6, 16.0))
      ->capture_default_str();
  errorTimeCmd
      ->add_option("--front-spp", errorTimeOptions.frontSpp,
                   "The reference spp whose blur-region error the front's hybrid-rays case must reach")
      ->check(CLI::Range(1u, 65536u))
      ->capture_default_str();

  PassesOptions passesOptions;
  CLI::App* passesCmd = app.add_subcommand(
      "passes", "Per-pass device time of each method, scene and image size, and each render's device memory");
  addCommonOptions(*passesCmd, passesOptions.out, passesOptions.warmup, passesOptions.repeats);
  addScenesOption(*passesCmd, passesOptions.scenes,
                  "Reference scenes, glTF files or " + std::string(hmb::bench::kMillionTriangles));
  passesCmd->add_option("--sizes", passesOptions.sizes, "Image sizes, WIDTHxHEIGHT, comma separated")
      ->delimiter(',')
      ->capture_default_str();
  passesCmd->add_option("--methods", passesOptions.methods,
                        "Methods (sharp, postprocess, hybrid, hybrid-rays; -curved: along curved paths), comma separated")
      ->delimiter(',')
      ->check(CLI::IsMember(hmb::bench::kPassesMethods))
      ->capture_default_str();

  EngineOptions engineOptions;
  CLI::App* engineCmd = app.add_subcommand(
      "engine", "The engine backend's post-process frame from an engine's G-buffer beside the command line's");
  addCommonOptions(*engineCmd, engineOptions.out, engineOptions.warmup, engineOptions.repeats);
  addScenesOption(*engineCmd, engineOptions.scenes, "Reference scenes or glTF files");
  engineCmd->add_option("--sizes", engineOptions.sizes, "Image sizes, WIDTHxHEIGHT, comma separated")
      ->delimiter(',')
      ->capture_default_str();

  ExplainOptions explainOptions;
  CLI::App* explainCmd = app.add_subcommand(
      "explain", "Where post-process's and hybrid's blur-region error against the reference comes from, by class");
  explainCmd->add_option("--out", explainOptions.out, "JSON report; the .md and the strips go beside it")
      ->capture_default_str();
  addScenesOption(*explainCmd, explainOptions.scenes);
  explainCmd->add_option("--size", explainOptions.size, "Image size, WIDTHxHEIGHT")->capture_default_str();
  explainCmd->add_option("--reference-spp", explainOptions.referenceSpp, "The reference's samples per pixel (even)")
      ->check(CLI::Range(2u, 65536u))
      ->capture_default_str();
  explainCmd->add_option("--methods", explainOptions.methods,
                         "Methods (postprocess, hybrid, hybrid-rays; -curved: along curved paths), comma separated")
      ->delimiter(',')
      ->check(CLI::IsMember(hmb::bench::kExplainMethods))
      ->capture_default_str();
  explainCmd->add_option("--tile-size", explainOptions.tileSize, "Every method's tile size in pixels (default: theirs)")
      ->check(CLI::Range(1u, HMB_MBLUR_MAX_TILE_SIZE));
  explainCmd->add_option("--time-slices", explainOptions.timeSlices, "The methods' time slices (K)")
      ->check(CLI::Range(1u, hmb::passes::kMaxTimeSlices))
      ->capture_default_str();

  KernelsOptions kernelsOptions;
  CLI::App* kernelsCmd = app.add_subcommand(
      "kernels", "Single kernels (raster, BVH build, trace, tile-max, gather) on synthetic inputs of chosen sizes");
  addCommonOptions(*kernelsCmd, kernelsOptions.out, kernelsOptions.suite.warmup, kernelsOptions.suite.repeats);
  kernelsCmd->add_option("--sizes", kernelsOptions.sizes, "Image sizes (raster, tile-max, gather), comma separated")
      ->delimiter(',')
      ->capture_default_str();
  kernelsCmd
      ->add_option("--triangles", kernelsOptions.suite.triangles,
                   "Triangle counts (raster, bvh-build, trace), comma separated")
      ->delimiter(',')
      ->check(CLI::Range(1u, 2000000u))
      ->capture_default_str();
  kernelsCmd->add_option("--rays", kernelsOptions.suite.rays, "Ray counts (trace), comma separated")
      ->delimiter(',')
      ->check(CLI::Range(1u, 1u << 26))
      ->capture_default_str();
  kernelsCmd->add_option("--kernels", kernelsOptions.suite.kernels, "Kernels to run, comma separated")
      ->delimiter(',')
      ->check(CLI::IsMember(hmb::bench::kernelNames()))
      ->capture_default_str();
  kernelsCmd
      ->add_option("--drivers", kernelsOptions.drivers,
                   "The same kernels on several drivers, side by side: 'default' (the installed one) or what "
                   "--driver-files takes, comma separated")
      ->delimiter(',');

  // `--suite NAME [options]` is the subcommand NAME spelled as an option. A first parse takes
  // the global options and --suite and leaves the rest, which the named suite's own parser
  // then takes. Its values can be suite names (--kernels raster), so they must not reach the
  // full parser, which would read them as subcommands.
  CLI::App suiteSpelling;
  suiteSpelling.set_help_flag();  // --help goes to the suite's parser (or to the full one)
  suiteSpelling.allow_extras();
  addGlobalOptions(suiteSpelling, global);
  suiteSpelling.add_option("--suite", suiteName);
  CLI::App* suite = nullptr;
  try {
    suiteSpelling.parse(argc, argv);
    if (suiteSpelling.count("--suite") == 0) {
      app.parse(argc, argv);
    } else {
      std::string names;
      for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) {
        names += (names.empty() ? "" : ", ") + command->get_name();
        if (command->get_name() == suiteName) suite = command;
      }
      if (!suite) {
        std::cerr << "hmblur-bench: error: unknown suite '" << suiteName << "' (suites: " << names << ")\n";
        return kError;
      }
      suite->parse(suiteSpelling.remaining_for_passthrough());
    }
  } catch (const CLI::ParseError& e) {
    return suite ? suite->exit(e) : app.exit(e);
  }

  try {
    // The driver is chosen before any Vulkan call: this may start the program again on it.
    if (!global.driverFiles.empty()) hmb::bench::runOnDriverFiles(global.driverFiles, argv);
    if (*rasterCmd) return raster(global, rasterOptions, commandLine(argc, argv));
    if (*bvhCmd) return bvh(global, bvhOptions, commandLine(argc, argv));
    if (*errorTimeCmd) return errorTime(global, errorTimeOptions, commandLine(argc, argv));
    if (*passesCmd) return passes(global, passesOptions, commandLine(argc, argv));
    if (*kernelsCmd) return kernels(global, kernelsOptions, commandLine(argc, argv));
    if (*engineCmd) return engine(global, engineOptions, commandLine(argc, argv));
    if (*explainCmd) return explain(global, explainOptions, commandLine(argc, argv));
  } catch (const std::exception& e) {
    std::cerr << "hmblur-bench: error: " << e.what() << '\n';
    return kError;
  }
  return kOk;
}
