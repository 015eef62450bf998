// hmblur: the command-line front end. Everything it does goes through the library API
// (include/hmblur/renderer.h); errors are one line on stderr and a non-zero exit.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "hmblur/context.h"
#include "hmblur/device_profile.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/setting.h"
#include "hmblur/renderer.h"
#include "hmblur/report.h"
#include "hmblur/system_info.h"
#include "runtime/cli/compare_command.h"
#include "runtime/cli/merge_command.h"
#include "runtime/cli/output_paths.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/io/image_files.h"
#include "runtime/io/labelled_strip.h"
#include "runtime/metrics/display_image.h"
#include "runtime/metrics/metrics.h"
#include "runtime/passes/hybrid_stage.h"
#include "runtime/sample_summary.h"
#include "scenes/reference_scenes.h"

namespace fs = std::filesystem;

namespace {

enum ExitCode { kOk = 0, kError = 1, kUsage = 2, kValidationFailed = 3 };

struct GlobalOptions {
  bool quiet = false;
  bool verbose = false;  // every pass of a render listed on stdout
  bool strict = false;  // what the loader leaves out is an error, not a warning
  int device = -1;
  bool validation = false;
  bool bindByAddress = false;
  std::string deviceProfile;  // auto, cpu or gpu; empty: HMB_DEVICE_PROFILE, else auto
};

struct RenderOptions {
  std::string scene = "living-room";
  std::string method = "sharp";
  hmb::RenderSettings settings;  // the method's settings: generated options (renderSettingDescriptions)
  std::string frames;            // "A:B": frames A to B at times frame / fps, an image each
  bool runEveryPass = false;
  std::string out;
  std::string report;
  std::string referenceImage;  // compare the result with this image (.exr or .png)
  std::string errorImage;      // FLIP error map of that comparison (.png)
  hmb::scene::ShutterChoice shutter;
  uint32_t repeat = 1;         // timed frames after the warm-up one; the median is printed
  bool shard = false;          // --shard: `out` is the part (and the shard's checkpoint)
};

struct DemoOptions {
  std::string scene;  // empty: the first reference scene
  std::optional<float> frameTime;
  std::string outDir = "out";
  uint32_t width = 640;
  uint32_t height = 360;
  uint32_t referenceSpp = 256;
};

void progress(const GlobalOptions& global, const std::string& message) {
  if (!global.quiet) std::cerr << "hmblur: " << message << '\n';
}

// The most loader warnings printed; the report lists them all.
constexpr size_t kMaxWarningsPrinted = 20;

// Loads the scene and says what the loader left out: each distinct warning once on stderr
// (none with --quiet); with --strict the first one is the error.
hmb::scene::Scene loadSceneSaying(const GlobalOptions& global, const std::string& name,
                                  const hmb::scene::ShutterChoice& shutter = {}) {
  progress(global, "loading scene " + name);
  hmb::scene::Scene scene = hmb::scene::loadScene(name, shutter);
  std::vector<std::string> distinct;
  for (const std::string& w : scene.stats.warnings)
    if (std::find(distinct.begin(), distinct.end(), w) == distinct.end()) distinct.push_back(w);
  if (global.strict && !distinct.empty())
    throw hmb::Error(name + ": " + distinct.front() + " (--strict; " + std::to_string(distinct.size()) +
                     " warning(s) in all)");
  if (!global.quiet) {
    for (size_t i = 0; i < std::min(distinct.size(), kMaxWarningsPrinted); ++i)
      std::cerr << "hmblur: warning: " << name << ": " << distinct[i] << '\n';
    if (distinct.size() > kMaxWarningsPrinted)
      std::cerr << "hmblur: warning: " << name << ": " << distinct.size() - kMaxWarningsPrinted
                << " more warnings (--report lists them all)\n";
  }
  return scene;
}

void writeImage(const fs::path& path, const hmb::RenderResult& result) {
  if (hmb::cli::lowerExtension(path) == ".exr")
    hmb::io::writeExr(path, result.image);
  else
    hmb::io::writePng(path, result.display);
}

hmb::vk::ContextOptions contextOptions(const GlobalOptions& global) {
  hmb::vk::ContextOptions options;
  options.deviceIndex = global.device;
  options.validation = global.validation;
  options.bindByAddress = global.bindByAddress;
  options.deviceProfile = hmb::vk::deviceProfileChoiceOrEnvironment(global.deviceProfile);
  return options;
}

// With --validation, any validation error fails the command after its work is done.
int validationVerdict(const hmb::vk::Context& context) {
  if (!context.validationEnabled() || context.validationErrors() == 0) return kOk;
  std::cerr << "hmblur: error: " << context.validationErrors() << " Vulkan validation error(s)\n";
  for (const std::string& message : context.validationMessages()) std::cerr << "  " << message << '\n';
  return kValidationFailed;
}

// Three significant digits at most: run-to-run noise is larger than the fourth.
std::string formatMs(const std::optional<double>& ms) {
  if (!ms) return "n/a";
  char text[32];
  std::snprintf(text, sizeof(text), *ms >= 100.0 ? "%.0f ms" : *ms >= 10.0 ? "%.1f ms" : "%.2f ms", *ms);
  return text;
}

// Progress of the reference on stderr: samples done, pixel samples taken per second, time
// left. Where only moving pixels take the later samples, the rate counts what was taken.
std::function<void(const hmb::passes::ReferenceProgress&)> referenceProgressPrinter(uint32_t width, uint32_t height) {
  using Clock = std::chrono::steady_clock;
  struct Start {
    Clock::time_point time;
    uint64_t pixelSamples = 0;
  };
  auto start = std::make_shared<std::optional<Start>>();
  auto lastPrint = std::make_shared<Clock::time_point>();
  return [=](const hmb::passes::ReferenceProgress& p) {
    const Clock::time_point now = Clock::now();
    // The first sample starts the clock, so rates count the samples after it.
    if (!*start) *start = Start{now, p.pixelSamples};
    const bool last = p.samplesDone == p.samplesTotal;
    if (!last && now - *lastPrint < std::chrono::seconds(2)) return;
    *lastPrint = now;
    const double seconds = std::chrono::duration<double>(now - (*start)->time).count();
    const double rate = seconds > 0.0 ? double(p.pixelSamples - (*start)->pixelSamples) / seconds : 0.0;
    const uint64_t perSample = p.movingPixels ? *p.movingPixels : uint64_t(width) * height;
    const double left = rate > 0.0 ? double(p.samplesTotal - p.samplesDone) * double(perSample) / rate : 0.0;
    char line[200];
    std::snprintf(line, sizeof(line), "hmblur: reference %u/%u spp, %.2f M pixel samples/s, %.0f s left", p.samplesDone,
                  p.samplesTotal, rate * 1e-6, left);
    std::string text = line;
    if (last && p.movingPixels)
      text += "; " + std::to_string(*p.movingPixels) + " of " + std::to_string(uint64_t(width) * height) +
              " pixels see motion and took every sample, the rest one (" + std::to_string(p.pixelSamples) +
              " pixel samples in all)";
    std::cerr << text << '\n';
  };
}

std::string metricsLine(const hmb::metrics::Comparison& c) {
  const auto number = [](const std::optional<double>& v, const char* format) {
    if (!v) return std::string("n/a");
    char text[32];
    std::snprintf(text, sizeof(text), format, *v);
    return std::string(text);
  };
  std::string line = "vs reference: PSNR " + number(c.frame.psnr, "%.2f dB") + ", SSIM " + number(c.frame.ssim, "%.4f") +
                     ", FLIP " + number(c.frame.flip, "%.4f");
  if (c.region)
    line += "; blur region (" + std::to_string(c.regionPixels) + " px): PSNR " + number(c.region->psnr, "%.2f dB") +
            ", SSIM " + number(c.region->ssim, "%.4f") + ", FLIP " + number(c.region->flip, "%.4f");
  return line + '\n';
}

int listDevices() {
  const auto devices = hmb::vk::Context::listDevices();
  if (devices.empty()) throw hmb::Error("no Vulkan device found (on Debian, mesa-vulkan-drivers provides lavapipe)");
  for (const auto& d : devices) {
    std::cout << d.index << ": " << d.name << " [" << d.type << "] Vulkan " << d.apiVersion;
    if (!d.driverName.empty()) std::cout << ", " << d.driverName;
    if (!d.driverInfo.empty()) std::cout << " (" << d.driverInfo << ")";
    std::cout << (d.computeCapable ? "" : ", no compute queue")
              << (d.preservesInfNan ? "" : ", cannot keep NaN and infinity in kernels (unusable)")
              << (d.int64BufferAtomics ? ", int64 atomics" : ", no int64 atomics")
              << (d.timestamps ? ", timestamps" : ", no timestamps") << '\n';
    // The profile a render there takes (the environment's HMB_DEVICE_PROFILE, else the device's).
    const hmb::vk::DeviceProfile profile =
        hmb::vk::makeDeviceProfile(d, d.maxComputeWorkGroupSizeX, d.maxComputeWorkGroupInvocations,
                                   hmb::vk::deviceProfileChoiceFromEnvironment());
    std::cout << "   profile " << profile.describe() << '\n';
  }
  return kOk;
}

int listScenes() {
  const auto list = [](const std::vector<std::string>& names) {
    for (const std::string& name : names) {
      const hmb::scene::Scene scene = hmb::scene::loadScene(name);
      std::cout << "  " << name << ": " << scene.triangleCount() << " triangles, " << scene.instances.size()
                << " instances, SOFT_Z_EXTENT " << scene.settings.softZExtent << ", e "
                << scene.settings.edgeThreshold << ", " << scene.settings.fps << " fps, exposure "
                << scene.settings.exposure << " s\n";
    }
  };
  std::cout << "reference scenes:\n";
  list(hmb::scene::referenceSceneNames());
  std::cout << "motion studies (one kind of screen motion each):\n";
  list(hmb::scene::motionStudyNames());
  std::cout << "(or any .gltf / .glb file)\n";
  return kOk;
}

struct FrameRange {
  uint32_t first = 0, last = 0;
};

// The largest animation one command renders: enough for minutes of film at 240 fps.
constexpr uint32_t kMaxFrames = 100000;

// "A:B" (0 <= A <= B) -> {A, B}; throws hmb::Error on anything else.
FrameRange parseFrames(const std::string& text) {
  const size_t colon = text.find(':');
  const auto number = [&](const std::string& part) {
    const auto digit = [](unsigned char c) { return std::isdigit(c) != 0; };
    if (part.empty() || part.size() > 9 || !std::all_of(part.begin(), part.end(), digit))
      throw hmb::Error("--frames '" + text + "' must be FIRST:LAST, two frame numbers");
    return static_cast<uint32_t>(std::stoul(part));
  };
  if (colon == std::string::npos) throw hmb::Error("--frames '" + text + "' must be FIRST:LAST, two frame numbers");
  const FrameRange range{number(text.substr(0, colon)), number(text.substr(colon + 1))};
  if (range.last < range.first) throw hmb::Error("--frames '" + text + "': the last frame is before the first");
  if (range.last - range.first >= kMaxFrames)
    throw hmb::Error("--frames '" + text + "': at most " + std::to_string(kMaxFrames) + " frames per command");
  return range;
}

// out.png, frame 7 of frames up to 120 -> out.0007.png (at least four digits, as many as the
// last frame needs).
fs::path framePath(const fs::path& out, uint32_t frame, uint32_t lastFrame) {
  const size_t digits = std::max<size_t>(4, std::to_string(lastFrame).size());
  std::string number = std::to_string(frame);
  number.insert(0, digits - number.size(), '0');
  return out.parent_path() / (out.stem().string() + "." + number + out.extension().string());
}

// Every pass of a frame with --verbose; else one line counting them.
void printPasses(const GlobalOptions& global, const hmb::FramePlan& plan) {
  if (!global.verbose) {
    size_t run = 0, skipped = 0;
    for (const auto& pass : plan.passes()) (pass.run ? run : skipped) += 1;
    std::cout << "  passes: " << run << " run, " << skipped << " left out (--verbose lists them)\n";
    return;
  }
  for (const auto& pass : plan.passes())
    std::cout << "  " << pass.name << ": "
              << (!pass.run ? "skipped (" + pass.reason + ")"
                  : !pass.within.empty()
                      ? "runs inside " + pass.within
                      : formatMs(pass.milliseconds) + (pass.noWork.empty() ? "" : " (no work: " + pass.noWork + ")"))
              << '\n';
}

// A frame where nothing moves on screen renders the sharp frame in every method: said on
// stderr, with the span of the scene's animation keys, where something may move. Returns
// whether the frame is still.
bool warnStillFrame(const GlobalOptions& global, const hmb::scene::Scene& scene, float frameTime) {
  if (hmb::anythingMovesOnScreen(scene, frameTime)) return false;
  if (global.quiet) return true;
  char text[160];
  std::snprintf(text, sizeof(text), "hmblur: warning: nothing moves on screen at t = %g s: every method gives the sharp frame",
                double(frameTime));
  std::cerr << text;
  float first = std::numeric_limits<float>::infinity(), last = -first;
  for (const hmb::scene::AnimationChannel& channel : scene.channels)
    for (const float t : channel.times) {
      first = std::min(first, t);
      last = std::max(last, t);
    }
  if (first < last) {
    std::snprintf(text, sizeof(text), "; the animation's keys span %g to %g s (--frame-time)", double(first),
                  double(last));
    std::cerr << text;
  } else {
    std::cerr << "; the scene has no animation";
  }
  std::cerr << '\n';
  return true;
}

// The blur region of a frame: where the reference differs from the sharp frame of the same
// instant. A still frame has none: there the two differ only where the raster and the ray
// trace break a silhouette's tie the other way, which is not blur.
hmb::metrics::BlurRegion blurRegionOf(const hmb::scene::Scene& scene, float frameTime,
                                      const hmb::metrics::DisplayImage& reference,
                                      const hmb::metrics::DisplayImage& sharp) {
  hmb::metrics::BlurRegion region = hmb::metrics::blurRegion(reference, sharp);
  if (!hmb::anythingMovesOnScreen(scene, frameTime)) {
    std::fill(region.inside.begin(), region.inside.end(), uint8_t(0));
    region.pixelCount = 0;
  }
  return region;
}

// Traces the device's loop limit cut short (RenderResult::cutTraces): said on stderr, as their
// pixels may be wrong.
void warnCutTraces(const GlobalOptions& global, const hmb::RenderResult& result) {
  if (global.quiet || result.cutTraces == 0) return;
  std::cerr << "hmblur: warning: " << result.cutTraces
            << " ray trace(s) cut short by the device's loop limit (Mesa 22.3's lavapipe ends a kernel "
               "invocation's loops after 65535 rounds): their pixels may be wrong; a newer Mesa has no such limit\n";
}

// --frames A:B: an image sequence, one renderer for all frames so that what a frame built and
// the next can use (the hybrid's trees) is kept. One report lists every frame's passes.
int renderFrames(const GlobalOptions& global, const RenderOptions& options, hmb::RenderSettings settings) {
  const FrameRange range = parseFrames(options.frames);
  const hmb::scene::Scene scene = loadSceneSaying(global, options.scene, options.shutter);
  hmb::vk::Context context(contextOptions(global));
  progress(global, hmb::deviceProgressLine(context));
  hmb::Renderer renderer(context);
  nlohmann::json report = {{"tool", "hmblur render --frames"},
                           {"date", hmb::utcTimestamp()},
                           {"device", hmb::deviceJson(context)},
                           {"system", hmb::systemJson(hmb::querySystemInfo())},
                           {"scene", hmb::sceneJson(scene)},
                           {"method", options.method},
                           {"resolution", {settings.width, settings.height}},
                           {"fps", scene.settings.fps},
                           {"frames", nlohmann::json::array()}};
  // Each frame's time is its own (frames[].time_s), not the scene's default.
  report["scene"]["settings"].erase("frame_time_s");
  bool warnedStill = false;  // once for the sequence
  for (uint32_t frame = range.first; frame <= range.last; ++frame) {
    settings.frameTime = static_cast<float>(frame / double(scene.settings.fps));
    const hmb::RenderResult result = renderer.render(scene, settings);
    if (!warnedStill) warnedStill = warnStillFrame(global, scene, *settings.frameTime);
    warnCutTraces(global, result);
    nlohmann::json entry = {{"frame", frame},
                            {"time_s", *settings.frameTime},
                            {"frame_ms", hmb::optionalNumber(result.frameMilliseconds)},
                            {"cut_traces", result.cutTraces},
                            {"passes", hmb::passesJson(result.plan)}};
    // The first frame compiles the kernels and builds every tree; the next ones keep them.
    std::string line = "frame " + std::to_string(frame) + ": " + formatMs(result.frameMilliseconds) +
                       (frame == range.first ? " (first frame: kernels compiled)" : "");
    const fs::path path = framePath(options.out, frame, range.last);
    writeImage(path, result);
    entry["image"] = path.string();
    line += " -> " + path.string();
    report["frames"].push_back(entry);
    progress(global, line);
  }
  if (!options.report.empty()) hmb::writeJson(options.report, report);
  return validationVerdict(context);
}

// The name an image gets without --out: the scene's (a reference name, or the file's stem)
// and the method's, in the working folder.
std::string defaultOutput(const std::string& scene, const std::string& method) {
  const fs::path path(scene);
  const std::string ext = hmb::cli::lowerExtension(path);
  const std::string stem = ext == ".gltf" || ext == ".glb" || fs::exists(path) ? path.stem().string() : scene;
  return stem + "-" + method + ".png";
}

// The untimed first frame of a method: lavapipe compiles a kernel at its first dispatch, so a
// method's first frame costs far more than the next. The reference takes one sample per pixel
// in it (a full one would double the command's time); the rest render the frame as asked.
hmb::RenderSettings warmUpSettings(hmb::RenderSettings settings) {
  settings.onProgress = nullptr;
  settings.reference.samplesPerPixel = 1;
  settings.reference.checkpoint.clear();
  settings.reference.shard = {};
  return settings;
}

struct TimedRender {
  hmb::RenderResult result;      // the last timed frame
  std::optional<double> coldMs;  // the warm-up frame's device time
  hmb::Summary frames;           // the timed frames' device times (none without timestamps)
  std::optional<double> medianMs() const {
    return frames.samples.empty() ? std::nullopt : std::optional<double>(frames.median);
  }
};

// A warm-up frame, then `repeat` timed ones, each paying what a new frame does (no trees kept
// from the frame before), as hmblur-bench times them.
TimedRender renderTimed(hmb::Renderer& renderer, const hmb::scene::Scene& scene, hmb::RenderSettings settings,
                        uint32_t repeat) {
  settings.reuseAcrossFrames = false;
  TimedRender timed;
  timed.coldMs = renderer.render(scene, warmUpSettings(settings)).frameMilliseconds;
  std::vector<double> framesMs;
  for (uint32_t i = 0; i < repeat; ++i) {
    timed.result = renderer.render(scene, settings);
    if (timed.result.frameMilliseconds) framesMs.push_back(*timed.result.frameMilliseconds);
  }
  timed.frames = hmb::summarize(std::move(framesMs));
  return timed;
}

nlohmann::json timingJson(const TimedRender& timed, hmb::Method method) {
  const bool any = !timed.frames.samples.empty();
  return {{"frames_ms", timed.frames.samples},
          {"median_ms", hmb::optionalNumber(timed.medianMs())},
          {"min_ms", any ? nlohmann::json(timed.frames.min) : nlohmann::json(nullptr)},
          {"max_ms", any ? nlohmann::json(timed.frames.max) : nlohmann::json(nullptr)},
          {"cold_ms", hmb::optionalNumber(timed.coldMs)},
          {"cold_frame", method == hmb::Method::Reference ? "1 sample per pixel, kernels compiled on first use"
                                                          : "the same frame, kernels compiled on first use"}};
}

// "<median> ms (median of <n>, <lowest> ms to <highest> ms; first frame <cold> ms, compiling
// kernels)": the warm time first, the cold one labelled.
std::string timingText(const TimedRender& timed, hmb::Method method) {
  const size_t n = timed.frames.samples.size();
  std::string text = formatMs(timed.medianMs()) + " (";
  if (n > 1)
    text += "median of " + std::to_string(n) + ", " + formatMs(timed.frames.min) + " to " +
            formatMs(timed.frames.max) + "; ";
  return text + "first frame " + formatMs(timed.coldMs) + (method == hmb::Method::Reference ? " at 1 spp" : "") +
         ", compiling kernels)";
}

// A method setting given for a method it does not belong to is an error naming its methods.
void requireSettingsOfTheMethod(const std::vector<std::pair<hmb::RenderSettingDescription, std::optional<std::string>>>& given,
                                hmb::Method method) {
  for (const auto& [description, text] : given) {
    if (!text || std::find(description.methods.begin(), description.methods.end(), method) != description.methods.end())
      continue;
    std::string owners;
    for (hmb::Method m : description.methods)
      owners += (owners.empty() ? "" : " or ") + std::string(hmb::methodName(m));
    throw hmb::Error("--" + description.name + " is a setting of --method " + owners + ", not of --method " +
                     std::string(hmb::methodName(method)));
  }
}

// What `render` was asked, checked before anything is read or written: a wrong value here is
// a usage error (exit 2), not a failure of the work.
void checkRenderArguments(const RenderOptions& options,
                          const std::vector<std::pair<hmb::RenderSettingDescription, std::optional<std::string>>>& given) {
  hmb::RenderSettings settings = options.settings;
  settings.method = hmb::parseMethod(options.method);
  requireSettingsOfTheMethod(given, settings.method);
  if (options.shard) {
    if (!options.frames.empty() || !options.referenceImage.empty() || options.repeat != 1)
      throw hmb::Error("--shard renders one part of one frame: --frames, --reference and --repeat do not apply");
    if (hmb::cli::lowerExtension(options.out) != ".hmbpart")
      throw hmb::Error("--shard writes a part for hmblur merge: --out names it (.hmbpart)");
  }
  hmb::validateRenderSettings(settings);
  if (options.repeat == 0 || options.repeat > 1000) throw hmb::Error("--repeat must be 1 to 1000");
  hmb::scene::Settings shutterCheck;
  hmb::scene::applyShutterChoice(options.shutter, shutterCheck);
  if (!options.frames.empty()) {
    parseFrames(options.frames);
    if (settings.frameTime)
      throw hmb::Error("--frames and --frame-time exclude each other: a frame's time is frame / fps");
    if (!options.referenceImage.empty() || !settings.reference.checkpoint.empty())
      throw hmb::Error("--frames renders a sequence: --reference and --checkpoint take one frame");
    if (options.repeat != 1) throw hmb::Error("--repeat times one frame; --frames renders each frame once");
  }
  if (!options.errorImage.empty() && options.referenceImage.empty())
    throw hmb::Error("--error-image needs --reference");
}

// After checkRenderArguments.
int render(const GlobalOptions& global, RenderOptions options) {
  hmb::RenderSettings settings = options.settings;
  settings.method = hmb::parseMethod(options.method);
  settings.skipUnneededPasses = !options.runEveryPass;
  if (!global.quiet) settings.onProgress = referenceProgressPrinter(settings.width, settings.height);
  if (options.out.empty()) options.out = defaultOutput(options.scene, options.method);
  if (options.shard)
    hmb::cli::prepareOutputFile(options.out, {".hmbpart"}, "--out");
  else
    hmb::cli::prepareOutputFile(options.out, {".exr", ".png"}, "--out");
  hmb::cli::prepareOutputFile(options.report, {".json"}, "--report");
  hmb::cli::prepareOutputFile(options.errorImage, {".png"}, "--error-image");
  if (!options.frames.empty()) return renderFrames(global, options, settings);
  // Read before rendering, so a bad reference fails at once.
  std::optional<hmb::metrics::DisplayImage> referenceImage;
  if (!options.referenceImage.empty()) {
    referenceImage = hmb::metrics::loadDisplayImage(options.referenceImage);
    if (referenceImage->width != settings.width || referenceImage->height != settings.height)
      throw hmb::Error("--reference '" + options.referenceImage + "' is " +
                       hmb::metrics::sizeText(referenceImage->width, referenceImage->height) + ", the render is " +
                       hmb::metrics::sizeText(settings.width, settings.height));
  }

  const hmb::scene::Scene scene = loadSceneSaying(global, options.scene, options.shutter);
  hmb::vk::Context context(contextOptions(global));
  progress(global, hmb::deviceProgressLine(context));
  hmb::Renderer renderer(context);
  progress(global, "rendering " + options.method + " at " + std::to_string(settings.width) + "x" +
                       std::to_string(settings.height));
  const TimedRender timed = renderTimed(renderer, scene, settings, options.repeat);
  const hmb::RenderResult& result = timed.result;
  warnStillFrame(global, scene, result.frameTime);
  warnCutTraces(global, result);

  if (!options.shard) writeImage(options.out, result);  // a shard's part is its checkpoint, written as it went
  nlohmann::json report = hmb::renderReport(context, hmb::querySystemInfo(), scene, result);
  report["timing"] = timingJson(timed, settings.method);
  report[options.shard ? "part" : "image"] = options.out;
  if (referenceImage) {
    // The blur region is where the reference differs from the sharp frame of the same instant.
    hmb::RenderSettings sharpSettings = settings;
    sharpSettings.method = hmb::Method::Sharp;
    sharpSettings.onProgress = nullptr;
    const hmb::metrics::DisplayImage sharp =
        hmb::metrics::displayImageFromRgba8(renderer.render(scene, sharpSettings).display);
    const hmb::metrics::BlurRegion region = blurRegionOf(scene, result.frameTime, *referenceImage, sharp);
    const hmb::metrics::Comparison comparison = hmb::metrics::compareImages(
        *referenceImage, hmb::metrics::displayImageFromLayered(result.image), &region);
    report["metrics"] = hmb::metrics::metricsJson(comparison);
    report["metrics"]["reference"] = options.referenceImage;
    if (!options.errorImage.empty()) hmb::io::writePng(options.errorImage, hmb::metrics::errorImage(comparison.flip));
    if (!global.quiet) std::cout << metricsLine(comparison);
  }
  if (!options.report.empty()) hmb::writeJson(options.report, report);
  if (!global.quiet) {
    std::cout << options.method << ": " << timingText(timed, settings.method) << " on " << context.info().name
              << " -> " << options.out << '\n';
    const hmb::vk::FrameShape& shape = result.frameShape;
    std::cout << "  frame shape: " << shape.dispatches << " dispatches (" << shape.indirectDispatches
              << " indirect), " << shape.barriers << " barriers, " << shape.hostWaits << " host waits, "
              << shape.dependentChain << " dependent dispatches in a chain\n";
    printPasses(global, result.plan);
  }
  return validationVerdict(context);
}

// The demo times each method by the median of nine frames: one frame's time moves by a third
// between runs here.
constexpr uint32_t kDemoTimedFrames = 9;

// A method's warm frame time and its blur-region PSNR against the reference.
struct CostAndGain {
  std::optional<double> frameMs;
  std::optional<double> regionPsnr;
};

CostAndGain costAndGain(const TimedRender& timed, const hmb::metrics::Comparison& comparison) {
  CostAndGain c{timed.medianMs(), std::nullopt};
  if (comparison.region && std::isfinite(comparison.region->psnr)) c.regionPsnr = comparison.region->psnr;
  return c;
}

struct HybridMethodsReport {
  nlohmann::json json;
  std::string line;  // one line for stdout
};

// The paper's hybrid and this project's extension, each frame over post-process's and its
// blur-region PSNR over post-process's, and what the extension buys over the paper's method,
// from `measured` (postprocess, hybrid, hybrid-rays).
HybridMethodsReport hybridMethodsReport(const std::map<std::string, CostAndGain>& measured) {
  const CostAndGain& post = measured.at("postprocess");
  using Number = std::optional<double>;
  const auto ratio = [](const Number& a, const Number& b) { return a && b && *b > 0.0 ? Number(*a / *b) : Number(); };
  const auto difference = [](const Number& a, const Number& b) { return a && b ? Number(*a - *b) : Number(); };
  // Printed numbers, or what stands for a missing one (no time stamps; an empty blur region).
  const auto printed = [](const Number& value, const char* format, const char* missing) {
    if (!value) return std::string(missing);
    char text[32];
    std::snprintf(text, sizeof(text), format, *value);
    return std::string(text);
  };
  HybridMethodsReport out;
  out.json = {{"what", "the paper's hybrid and the shutter-ray extension: each frame over post-process's and its "
                       "blur-region PSNR against the reference over post-process's, measured in this run"},
              {"postprocess", {{"frame_ms", hmb::optionalNumber(post.frameMs)},
                               {"blur_region_psnr_db", hmb::optionalNumber(post.regionPsnr)}}},
              {"methods", nlohmann::json::array()}};
  out.line = "hybrid methods:";
  for (const auto& [method, what] : {std::pair<const char*, const char*>{"hybrid", "the paper's method"},
                                     {"hybrid-rays", "the shutter-ray extension"}}) {
    const CostAndGain& m = measured.at(method);
    const Number times = ratio(m.frameMs, post.frameMs);
    const Number gain = difference(m.regionPsnr, post.regionPsnr);
    out.json["methods"].push_back({{"method", method},
                                   {"what", what},
                                   {"frame_ms", hmb::optionalNumber(m.frameMs)},
                                   {"x_postprocess", hmb::optionalNumber(times)},
                                   {"blur_region_psnr_db", hmb::optionalNumber(m.regionPsnr)},
                                   {"over_postprocess_db", hmb::optionalNumber(gain)}});
    out.line += " " + std::string(method) + " (" + what + ") " + printed(times, "%.2fx", "untimed against") +
                " post-process's frame, " + printed(gain, "%+.1f dB", "no blur region") + " over it in the blur region;";
  }
  const CostAndGain& paper = measured.at("hybrid");
  const CostAndGain& rays = measured.at("hybrid-rays");
  const Number buys = difference(rays.regionPsnr, paper.regionPsnr);
  const Number costs = ratio(rays.frameMs, paper.frameMs);
  out.json["extension_buys"] = {{"blur_region_db", hmb::optionalNumber(buys)},
                                {"x_paper_frame", hmb::optionalNumber(costs)}};
  out.line.back() = ':';
  out.line += " the rays buy " + printed(buys, "%+.1f dB", "an unmeasured gain") + " for " +
              printed(costs, "%.2fx", "an untimed share of") + " the paper's frame";
  return out;
}

// The main job: the default scene with every method this build has, images and one report.
int demo(const GlobalOptions& global, const DemoOptions& options) {
  hmb::cli::prepareOutputFolder(options.outDir, "--out-dir");
  const std::string sceneArgument = options.scene.empty() ? hmb::scene::referenceSceneNames().front() : options.scene;
  // A glTF file's outputs are named after its stem.
  const std::string sceneName = fs::path(sceneArgument).extension().empty() ? sceneArgument
                                                                             : fs::path(sceneArgument).stem().string();
  const hmb::scene::Scene scene = loadSceneSaying(global, sceneArgument);
  warnStillFrame(global, scene, options.frameTime.value_or(scene.settings.frameTime));
  hmb::vk::Context context(contextOptions(global));
  progress(global, hmb::deviceProgressLine(context));
  hmb::Renderer renderer(context);

  const hmb::SystemInfo system = hmb::querySystemInfo();
  nlohmann::json report = {{"tool", "hmblur demo"},
                           {"date", hmb::utcTimestamp()},
                           {"device", hmb::deviceJson(context)},
                           {"system", hmb::systemJson(system)},
                           {"scene", hmb::sceneJson(scene)},
                           {"methods", nlohmann::json::array()}};
  // The reference first: it is the judge every other method is measured against.
  std::vector<std::string> methods = hmb::methodNames();
  std::stable_partition(methods.begin(), methods.end(),
                        [](const std::string& m) { return hmb::parseMethod(m) == hmb::Method::Reference; });
  std::optional<hmb::metrics::DisplayImage> judge, sharp;
  std::map<std::string, hmb::io::CaptionedImage> stripPanels;
  std::map<std::string, CostAndGain> measured;  // each method's cost and gain, for the hybrid methods' report
  for (const std::string& method : methods) {
    hmb::RenderSettings settings;
    settings.method = hmb::parseMethod(method);
    settings.width = options.width;
    settings.height = options.height;
    settings.frameTime = options.frameTime;
    settings.reference.samplesPerPixel = options.referenceSpp;
    if (!global.quiet) settings.onProgress = referenceProgressPrinter(options.width, options.height);
    progress(global, "rendering " + method);
    // The reference, seconds long, is timed once.
    const uint32_t repeat = settings.method == hmb::Method::Reference ? 1 : kDemoTimedFrames;
    const TimedRender timed = renderTimed(renderer, scene, settings, repeat);
    const hmb::RenderResult& result = timed.result;
    warnCutTraces(global, result);
    const fs::path stem = fs::path(options.outDir) / (sceneName + "-" + method);
    hmb::io::writePng(stem.string() + ".png", result.display);
    hmb::io::writeExr(stem.string() + ".exr", result.image);
    hmb::io::CaptionedImage& panel = stripPanels[method];
    panel.image = result.display;
    panel.caption = {settings.method == hmb::Method::Reference
                         ? method + " (" + std::to_string(options.referenceSpp) + " spp)"
                         : method,
                     formatMs(timed.medianMs())};
    const hmb::metrics::DisplayImage display = hmb::metrics::displayImageFromLayered(result.image);
    if (settings.method == hmb::Method::Reference) judge = display;
    if (settings.method == hmb::Method::Sharp) sharp = display;
    nlohmann::json entry = {{"method", method},
                            {"frame_time_s", result.frameTime},
                            {"frame_ms", hmb::optionalNumber(result.frameMilliseconds)},
                            {"cut_traces", result.cutTraces},
                            {"timing", timingJson(timed, settings.method)},
                            {"settings", hmb::methodSettingsJson(result)},
                            {"passes", hmb::passesJson(result.plan)},
                            {"raster", hmb::rasterJson(result)},
                            {"images", {stem.string() + ".png", stem.string() + ".exr"}}};
    std::string line = method + ": " + timingText(timed, settings.method);
    if (judge && method != "reference") {
      const hmb::metrics::BlurRegion region = blurRegionOf(scene, result.frameTime, *judge, sharp.value_or(display));
      const hmb::metrics::Comparison comparison = hmb::metrics::compareImages(*judge, display, &region);
      measured[method] = costAndGain(timed, comparison);
      entry["metrics"] = hmb::metrics::metricsJson(comparison);
      hmb::io::writePng(stem.string() + "-error.png", hmb::metrics::errorImage(comparison.flip));
      const std::string metrics = metricsLine(comparison);
      line += ", " + metrics.substr(0, metrics.size() - 1);
      char psnr[48];
      std::snprintf(psnr, sizeof(psnr), ", PSNR %.1f dB", comparison.frame.psnr);
      panel.caption[1] += std::isfinite(comparison.frame.psnr) ? psnr : ", identical";
    }
    report["methods"].push_back(entry);
    if (!global.quiet) std::cout << line << " -> " << stem.string() << ".png\n";
  }
  // The paper's method and the extension side by side: what the rays cost and buy, in this run.
  if (measured.count("postprocess") && measured.count("hybrid") && measured.count("hybrid-rays")) {
    const HybridMethodsReport methodsReport = hybridMethodsReport(measured);
    report["hybrid_methods"] = methodsReport.json;
    if (!global.quiet) std::cout << methodsReport.line << '\n';
  }
  // Side by side, sharp to reference, each captioned with its method, warm time and PSNR
  // against the reference: what a newcomer looks at first.
  std::vector<hmb::io::CaptionedImage> panels;
  for (const std::string& m : hmb::methodNames()) panels.push_back(stripPanels.at(m));
  const hmb::io::LabelledStrip strip = hmb::io::labelledStrip(panels);
  if (!strip.captioned && !global.quiet)
    std::cerr << "hmblur: warning: no sans-serif font found (fontconfig): the strip's captions are left out\n";
  const fs::path stripPath = fs::path(options.outDir) / (sceneName + "-strip.png");
  hmb::io::writePng(stripPath, strip.image);
  report["strip"] = {{"image", stripPath.string()}, {"order", hmb::methodNames()}, {"captioned", strip.captioned}};
  if (!global.quiet) std::cout << "strip (" << [&] {
    std::string names;
    for (const std::string& m : hmb::methodNames()) names += (names.empty() ? "" : ", ") + m;
    return names;
  }() << ", captioned with time and PSNR): " << stripPath.string() << '\n';
  const fs::path reportPath = fs::path(options.outDir) / "report.json";
  hmb::writeJson(reportPath, report);
  if (!global.quiet) std::cout << "report: " << reportPath.string() << '\n';
  return validationVerdict(context);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"hybrid-mblur: motion blur by post-process, hybrid ray reveal and distributed ray tracing, "
               "all in Vulkan compute"};
  app.require_subcommand(1);
  app.fallthrough();
  app.set_version_flag("--version", std::string("hmblur ") + HMB_VERSION);
  GlobalOptions global;
  app.add_flag("-q,--quiet", global.quiet, "Print nothing but errors and results (no progress, no warnings)");
  app.add_flag("-v,--verbose", global.verbose, "List every pass of a render on stdout: run or left out, why, its time");
  app.add_flag("--strict", global.strict,
               "Refuse a scene the loader cannot draw whole: every warning (a skipped primitive, an ignored "
               "extension or material property) is an error");
  app.add_option("--device", global.device, "Vulkan device index (see list-devices); default: best compute device")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--validation", global.validation,
               "Enable the Khronos validation layer; any validation error fails the command");
  app.add_flag("--bind-by-address", global.bindByAddress,
               "Kernels with an address build bind their groups of buffers as tables of device addresses "
               "(default: only where the device has too few storage-buffer bindings)");
  app.add_option("--device-profile", global.deviceProfile,
                 "Whose choices the passes make: auto (the device type's), cpu or gpu (forced, so a GPU's "
                 "choices run on a CPU device and the other way round); default: HMB_DEVICE_PROFILE, else auto")
      ->check(CLI::IsMember({"auto", "cpu", "gpu"}));

  RenderOptions renderOptions;
  CLI::App* renderCmd = app.add_subcommand("render", "Render one frame of a scene with one method");
  renderCmd->add_option("--scene", renderOptions.scene, "Reference scene name or a .gltf/.glb file")
      ->capture_default_str();
  std::string methodHelp = "Rendering method:";
  for (const hmb::MethodDescription& m : hmb::methodDescriptions())
    methodHelp += "\n  " + std::string(m.name) + ": " + std::string(m.summary);
  renderCmd->add_option("--method", renderOptions.method, methodHelp)->capture_default_str();
  renderCmd->add_option("--width", renderOptions.settings.width, "Image width in pixels")->capture_default_str();
  renderCmd->add_option("--height", renderOptions.settings.height, "Image height in pixels")->capture_default_str();
  renderCmd->add_option("--frame-time", renderOptions.settings.frameTime,
                        "Time of the frame in seconds (shutter closes then); default: the scene's");
  using hmb::settings::formatNumber;
  using hmb::scene::kGltfFps, hmb::scene::kGltfShutterAngleDegrees;
  renderCmd->add_option("--fps", renderOptions.shutter.fps,
                        "Frame rate: the previous frame, whose positions give the post-process methods their "
                        "velocities, is 1/fps before; default: the scene's (a glTF file: " +
                            formatNumber(kGltfFps) + ")");
  renderCmd->add_option("--exposure", renderOptions.shutter.exposureSeconds,
                        "Shutter open time in seconds, ending at the frame time: the span every method blurs "
                        "over; default: the scene's (a glTF file: a " +
                            formatNumber(kGltfShutterAngleDegrees) + "-degree shutter, 1/" +
                            formatNumber(kGltfFps * 360.0f / kGltfShutterAngleDegrees) + " s)")
      ->type_name("SECONDS");
  renderCmd->add_option("--shutter-angle", renderOptions.shutter.shutterAngleDegrees,
                        "The exposure as a shutter angle: 360 degrees is the whole frame interval (1/fps)")
      ->type_name("DEGREES");
  renderCmd->add_option("--repeat", renderOptions.repeat,
                        "Time the frame this many times after an untimed first one; prints the median")
      ->capture_default_str();
  renderCmd->add_option("--frames", renderOptions.frames,
                        "Render frames FIRST:LAST (at frame / fps) as an image sequence: --out NAME.png writes "
                        "NAME.0001.png ...; the report lists every frame");
  renderCmd->add_flag("--run-every-pass", renderOptions.runEveryPass,
                      "Run the passes that cannot change this frame too (by default they are skipped; the report "
                      "says which and why)");
  renderCmd->add_option("--out", renderOptions.out,
                        "Output image: .exr (beauty + AOV layers) or .png (display); default: SCENE-METHOD.png "
                        "in the working folder. Missing folders are made");
  renderCmd->add_option("--report", renderOptions.report, "JSON report: device, settings, per-pass times");
  // Every method setting, from its one description; read once the command line is parsed.
  std::vector<std::pair<hmb::RenderSettingDescription, std::optional<std::string>>> methodSettings;
  for (const hmb::RenderSettingDescription& d : hmb::renderSettingDescriptions()) methodSettings.emplace_back(d, std::nullopt);
  for (auto& [description, text] : methodSettings) {
    if (description.flag)
      renderCmd->add_flag_callback("--" + description.name, [&text = text] { text = "true"; }, description.help);
    else
      renderCmd->add_option("--" + description.name, text, description.help)->type_name(description.valueName);
  }
  renderCmd->add_option("--reference", renderOptions.referenceImage,
                        "Compare the result with this image (.exr or .png): PSNR, SSIM, FLIP in the report");
  renderCmd->add_option("--error-image", renderOptions.errorImage, "With --reference: write the FLIP error map (.png)");

  DemoOptions demoOptions;
  CLI::App* demoCmd = app.add_subcommand("demo", "Render the default scene with every method and write a report");
  demoCmd->add_option("--scene", demoOptions.scene,
                      "Reference scene name or glTF file (default: " + hmb::scene::referenceSceneNames().front() + ")");
  demoCmd->add_option("--frame-time", demoOptions.frameTime, "Frame time in seconds (default: the scene's)");
  demoCmd->add_option("--out-dir", demoOptions.outDir, "Output folder")->capture_default_str();
  demoCmd->add_option("--width", demoOptions.width, "Image width in pixels")->capture_default_str();
  demoCmd->add_option("--height", demoOptions.height, "Image height in pixels")->capture_default_str();
  demoCmd->add_option("--spp", demoOptions.referenceSpp, "Samples per pixel of the reference")->capture_default_str();

  CLI::App* listScenesCmd = app.add_subcommand("list-scenes", "List the built-in reference scenes");
  CLI::App* listDevicesCmd = app.add_subcommand("list-devices", "List the Vulkan devices");
  hmb::cli::CompareOptions compareOptions;
  CLI::App* compareCmd = hmb::cli::addCompareCommand(app, compareOptions);
  hmb::cli::MergeOptions mergeOptions;
  CLI::App* mergeCmd = hmb::cli::addMergeCommand(app, mergeOptions);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the help, the version or the error
    return code == 0 ? kOk : kUsage;
  }

  try {
    for (const auto& [description, text] : methodSettings) {
      if (!text) continue;
      description.read(renderOptions.settings, *text);
      if (description.name == "shard") renderOptions.shard = true;
    }
    if (renderOptions.shard) {
      // The part is the shard's checkpoint: the same command again resumes it.
      if (!renderOptions.settings.reference.checkpoint.empty())
        throw hmb::Error("with --shard, --out is the shard's checkpoint: leave out --checkpoint");
      renderOptions.settings.reference.checkpoint = renderOptions.out;
    }
    if (*renderCmd) checkRenderArguments(renderOptions, methodSettings);
    if (*mergeCmd) hmb::cli::checkMergeArguments(mergeOptions);
  } catch (const std::exception& e) {
    std::cerr << "hmblur: error: " << e.what() << '\n';
    return kUsage;
  }

  try {
    if (*listDevicesCmd) return listDevices();
    if (*listScenesCmd) return listScenes();
    if (*renderCmd) return render(global, renderOptions);
    if (*demoCmd) return demo(global, demoOptions);
    if (*compareCmd) return hmb::cli::runCompare(compareOptions);
    if (*mergeCmd) {
      hmb::vk::Context context(contextOptions(global));
      progress(global, hmb::deviceProgressLine(context));
      hmb::cli::runMerge(mergeOptions, context, global.quiet);
      return validationVerdict(context);
    }
  } catch (const std::exception& e) {
    std::cerr << "hmblur: error: " << e.what() << '\n';
    return kError;
  }
  return kOk;
}
