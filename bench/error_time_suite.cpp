#include "bench/error_time_suite.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bench/bench_scenes.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "runtime/io/image_files.h"
#include "runtime/metrics/display_image.h"
#include "runtime/metrics/metrics.h"
#include "runtime/passes/reference_stage.h"

namespace fs = std::filesystem;

namespace hmb::bench {
namespace {

struct Config {
  std::string label, series;
  double parameter = 0;
  RenderSettings settings;
};

// Every configuration of one scene, in plot order: sharp, the post-process series (centred,
// adapted, adapted along curved paths) and hybrid series, then the reference's spp series.
std::vector<Config> configurations(const ErrorTimeSuiteOptions& o) {
  std::vector<Config> configs;
  const auto add = [&](std::string label, std::string series, double parameter, const std::string& method) {
    Config c{std::move(label), std::move(series), parameter, {}};
    c.settings.method = parseMethod(method);
    // Each repeat is timed as a new frame of the animation: nothing kept from the last one.
    c.settings.reuseAcrossFrames = false;
    c.settings.width = o.size.width;
    c.settings.height = o.size.height;
    configs.push_back(std::move(c));
    return &configs.back().settings;
  };
  add("sharp", "sharp", 0, "sharp");
  for (const passes::GatherRange range : {passes::GatherRange::Centered, passes::GatherRange::Adapted})
    for (const uint32_t s : o.samples) {
      const std::string name = "postprocess " + std::string(passes::rangeName(range));
      RenderSettings* settings = add(name + " S" + std::to_string(s), name, s, "postprocess");
      settings->postprocess.range = range;
      settings->postprocess.samples = s;
    }
  for (const uint32_t s : o.samples) {
    RenderSettings* settings = add("postprocess curved S" + std::to_string(s), "postprocess curved path", s, "postprocess");
    settings->postprocess.motionPath = passes::MotionPath::Curved;
    settings->postprocess.samples = s;
  }
  for (const uint32_t s : o.samples) add("hybrid S" + std::to_string(s), "hybrid", s, "hybrid")->postprocess.samples = s;
  for (const uint32_t s : o.samples)
    add("hybrid-rays S" + std::to_string(s), "hybrid-rays", s, "hybrid-rays")->postprocess.samples = s;
  // The reveal's settings act on the paper's hybrid (hybrid-rays leaves the mask to its rays).
  for (const uint32_t r : o.recursionLimits) {
    RenderSettings* settings = add("hybrid luminance stop R" + std::to_string(r), "hybrid luminance stop", r, "hybrid");
    settings->hybrid.stop = passes::RevealStop::Luminance;
    settings->hybrid.maxRecursion = r;
  }
  for (const float e : o.edgeThresholds)
    add("hybrid e" + fixed(e, 2), "hybrid edge threshold", e, "hybrid")->hybrid.edgeThreshold = e;
  for (const uint32_t n : o.shutterRays)
    add("hybrid-rays strata " + std::to_string(n), "hybrid-rays strata", n, "hybrid-rays")->hybrid.shutterRays = n;
  const double pixels = double(o.size.width) * o.size.height;
  for (const double perPixel : o.rayBudgets) {
    const uint32_t budget = uint32_t(std::clamp(std::round(perPixel * pixels), 2.0, 4294967295.0));
    add("hybrid-rays budget " + fixed(perPixel, 3) + "/px", "hybrid-rays ray budget", perPixel, "hybrid-rays")
        ->hybrid.rayBudget = budget;
  }
  for (const uint32_t k : o.timeSlices) {
    add("postprocess adapted K" + std::to_string(k), "postprocess adapted time slices", k, "postprocess")
        ->postprocess.timeSlices = k;
    add("hybrid K" + std::to_string(k), "hybrid time slices", k, "hybrid")->postprocess.timeSlices = k;
  }
  for (const uint32_t spp : o.referenceSpp) {
    RenderSettings* settings = add("reference " + std::to_string(spp) + " spp", "reference", spp, "reference");
    settings->reference.samplesPerPixel = spp;
    settings->reference.seed = 2;
  }
  return configs;
}

metrics::DisplayImage displayOf(const RenderResult& r) { return metrics::displayImageFromRgba8(r.display); }

// The frame's device time without the per-scene setup (the meshes' BVHs, built once per scene):
// the hybrid's frame time leaves it out already, the reference's counts it, so it is taken out
// here for both to be timed alike.
double frameMillisecondsWithoutSetup(const RenderResult& r) {
  double ms = *r.frameMilliseconds;
  if (r.method == Method::Reference)
    for (const PlannedPass& pass : r.plan.passes())
      if (pass.name == passes::ReferenceStage::kBvhMeshes && pass.milliseconds) ms -= *pass.milliseconds;
  return ms;
}

ErrorTimeScene runScene(Renderer& renderer, const std::string& name, const ErrorTimeSuiteOptions& o,
                        const Progress& progress) {
  const scene::Scene scene = scene::loadScene(name);
  ErrorTimeScene result;
  result.scene = name;
  metrics::DisplayImage judge;
  if (!o.referenceDir.empty()) {
    const fs::path path = fs::path(o.referenceDir) / (sceneStem(name) + "-reference.exr");
    judge = metrics::loadDisplayImage(path);
    if (judge.width != o.size.width || judge.height != o.size.height)
      throw Error("judge " + path.string() + " is " + metrics::sizeText(judge.width, judge.height) + ", not " +
                  metrics::sizeText(o.size.width, o.size.height));
    result.judge = path.filename().string();
  } else {
    RenderSettings settings;
    settings.method = Method::Reference;
    settings.width = o.size.width;
    settings.height = o.size.height;
    settings.reference.samplesPerPixel = o.judgeSpp;
    settings.reference.seed = 1;
    settings.onProgress = [&](const passes::ReferenceProgress& p) {
      if (p.samplesDone % 64 == 0 || p.samplesDone == p.samplesTotal)
        progress(name + ": judge " + std::to_string(p.samplesDone) + "/" + std::to_string(p.samplesTotal) + " spp");
    };
    judge = displayOf(renderer.render(scene, settings));
    result.judge = "rendered here, " + std::to_string(o.judgeSpp) + " spp, seed 1";
  }

  std::optional<metrics::BlurRegion> region;
  for (const Config& config : configurations(o)) {
    const bool reference = config.settings.method == Method::Reference;
    const int warmup = reference ? 0 : o.warmup;
    const int repeats = reference ? o.referenceRepeats : o.repeats;
    progress(name + ": " + config.label);
    std::vector<double> times;
    RenderResult last;
    for (int i = 0; i < warmup + repeats; ++i) {
      last = renderer.render(scene, config.settings);
      if (!last.frameMilliseconds) throw Error("the device gives no timestamps: frame times cannot be measured");
      if (i >= warmup) times.push_back(frameMillisecondsWithoutSetup(last));
    }
    const metrics::DisplayImage image = displayOf(last);
    if (!region) region = metrics::blurRegion(judge, image);  // the first case is the sharp frame
    const metrics::Comparison error = metrics::compareImages(judge, image, &*region);
    ErrorTimeCase c;
    c.scene = name;
    c.method = std::string(methodName(config.settings.method));
    c.label = config.label;
    c.series = config.series;
    c.parameter = config.parameter;
    c.frameMilliseconds = summarize(times);
    c.framePsnr = error.frame.psnr;
    c.frameSsim = error.frame.ssim.value_or(NAN);
    if (error.region) {
      c.regionPsnr = error.region->psnr;
      c.regionSsim = error.region->ssim;
    }
    if (last.hybrid) {
      c.maskPixels = last.hybrid->maskPixels;
      c.revealRays = last.hybrid->revealRays;
      c.shutterRays = last.hybrid->shutterRays;
    }
    result.cases.push_back(std::move(c));
  }
  result.regionPixels = region ? region->pixelCount : 0;

  // Each hybrid at its defaults: its samples series' case at the default sample count.
  const uint32_t defaultSamples = passes::PostProcessSettings{}.samples;
  for (const char* method : {"hybrid", "hybrid-rays"}) {
    const auto hybrid = std::find_if(result.cases.begin(), result.cases.end(), [&](const ErrorTimeCase& c) {
      return c.series == method && c.parameter == defaultSamples;
    });
    if (hybrid == result.cases.end() || !hybrid->regionPsnr) continue;
    ErrorTimeScene::Match m;
    m.method = method;
    m.hybridRegionPsnr = *hybrid->regionPsnr;
    m.hybridMilliseconds = hybrid->frameMilliseconds.median;
    for (const ErrorTimeCase& c : result.cases) {
      if (c.series != "reference" || !c.regionPsnr) continue;
      m.referenceMilliseconds = c.frameMilliseconds.median;
      if (*c.regionPsnr >= m.hybridRegionPsnr) {
        m.spp = static_cast<uint32_t>(c.parameter);
        break;
      }
    }
    m.timeRatio = m.hybridMilliseconds > 0 ? m.referenceMilliseconds / m.hybridMilliseconds : NAN;
    result.matches.push_back(m);
  }
  // The front against the reference at frontSpp.
  const auto reference = std::find_if(result.cases.begin(), result.cases.end(), [&](const ErrorTimeCase& c) {
    return c.series == "reference" && c.parameter == o.frontSpp && c.regionPsnr;
  });
  if (reference != result.cases.end()) {
    ErrorTimeScene::Front f;
    f.spp = o.frontSpp;
    f.referenceRegionPsnr = *reference->regionPsnr;
    f.referenceMilliseconds = reference->frameMilliseconds.median;
    for (const ErrorTimeCase& c : result.cases) {
      if (c.method != "hybrid-rays" || !c.regionPsnr || *c.regionPsnr < f.referenceRegionPsnr) continue;
      if (f.label && c.frameMilliseconds.median >= f.milliseconds) continue;
      f.label = c.label;
      f.regionPsnr = *c.regionPsnr;
      f.milliseconds = c.frameMilliseconds.median;
    }
    f.timeRatio = f.label && f.milliseconds > 0 ? f.referenceMilliseconds / f.milliseconds : NAN;
    result.front = f;
  }
  return result;
}

nlohmann::json optionalJson(const std::optional<double>& value) {
  return value && std::isfinite(*value) ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

std::string optionalText(const std::optional<double>& value, int digits) {
  return value && std::isfinite(*value) ? fixed(*value, digits) : "-";
}

}  // namespace

std::vector<ErrorTimeScene> runErrorTimeSuite(vk::Context& context, const ErrorTimeSuiteOptions& options,
                                              const Progress& progress) {
  if (options.repeats < 1 || options.referenceRepeats < 1) throw Error("error-vs-time: repeats must be at least 1");
  if (options.scenes.empty()) throw Error("error-vs-time: no scenes");
  Renderer renderer(context);
  std::vector<ErrorTimeScene> scenes;
  for (const std::string& scene : options.scenes) scenes.push_back(runScene(renderer, scene, options, progress));
  return scenes;
}

nlohmann::json errorTimeSceneJson(const ErrorTimeScene& s) {
  nlohmann::json j = {{"scene", s.scene}, {"judge", s.judge}, {"region_pixels", s.regionPixels},
                      {"cases", nlohmann::json::array()}, {"hybrid_vs_reference", nlohmann::json::array()},
                      {"front", nullptr}};
  for (const ErrorTimeCase& c : s.cases) {
    nlohmann::json entry = {{"method", c.method},
                            {"label", c.label},
                            {"series", c.series},
                            {"parameter", c.parameter},
                            {"frame_ms", summaryJson(c.frameMilliseconds)},
                            {"frame", {{"psnr_db", optionalJson(c.framePsnr)}, {"ssim", optionalJson(c.frameSsim)}}},
                            {"region", {{"psnr_db", optionalJson(c.regionPsnr)}, {"ssim", optionalJson(c.regionSsim)}}}};
    if (c.method == "hybrid") {
      entry["mask_pixels"] = c.maskPixels;
      entry["reveal_rays"] = c.revealRays;
    }
    if (c.method == "hybrid-rays") entry["shutter_rays_traced"] = c.shutterRays;
    j["cases"].push_back(std::move(entry));
  }
  for (const ErrorTimeScene::Match& m : s.matches)
    j["hybrid_vs_reference"].push_back({{"method", m.method},
                                        {"hybrid_region_psnr_db", m.hybridRegionPsnr},
                                        {"hybrid_ms", m.hybridMilliseconds},
                                        {"matching_spp", m.spp ? nlohmann::json(*m.spp) : nlohmann::json(nullptr)},
                                        {"reference_ms", m.referenceMilliseconds},
                                        {"time_ratio", optionalJson(m.timeRatio)}});
  if (s.front)
    j["front"] = {{"reference_spp", s.front->spp},
                  {"reference_region_psnr_db", s.front->referenceRegionPsnr},
                  {"reference_ms", s.front->referenceMilliseconds},
                  {"label", s.front->label ? nlohmann::json(*s.front->label) : nlohmann::json(nullptr)},
                  {"region_psnr_db", s.front->label ? nlohmann::json(s.front->regionPsnr) : nlohmann::json(nullptr)},
                  {"ms", s.front->label ? nlohmann::json(s.front->milliseconds) : nlohmann::json(nullptr)},
                  {"time_ratio", optionalJson(s.front->timeRatio)}};
  return j;
}

void writeErrorTimeCsv(std::ostream& out, const std::vector<ErrorTimeScene>& scenes) {
  out << "scene,method,label,series,parameter,median_ms,frame_psnr_db,frame_ssim,region_psnr_db,region_ssim\n";
  for (const ErrorTimeScene& s : scenes)
    for (const ErrorTimeCase& c : s.cases)
      out << s.scene << ',' << c.method << ',' << c.label << ',' << c.series << ',' << c.parameter << ','
          << fixed(c.frameMilliseconds.median, 3) << ',' << optionalText(c.framePsnr, 3) << ','
          << optionalText(c.frameSsim, 4) << ',' << optionalText(c.regionPsnr, 3) << ','
          << optionalText(c.regionSsim, 4) << '\n';
}

void writeErrorTimeMarkdown(std::ostream& out, const std::vector<ErrorTimeScene>& scenes, const std::string& context) {
  out << "# Error against run time\n\n" << context << "\n";
  for (const ErrorTimeScene& s : scenes) {
    out << "\n## " << s.scene << "\n\nJudge: " << s.judge << "; blur region " << s.regionPixels << " pixels.\n\n";
    for (const ErrorTimeScene::Match& m : s.matches) {
      out << m.method << " (defaults) reaches " << fixed(m.hybridRegionPsnr, 2) << " dB over the blur region in "
          << fixed(m.hybridMilliseconds, 1) << " ms. ";
      if (m.spp)
        out << "The reference first matches it at " << *m.spp << " spp, in " << fixed(m.referenceMilliseconds, 1)
            << " ms: **" << fixed(m.timeRatio, 1) << "x** its time.\n\n";
      else
        out << "No reference tried matches it; the largest took " << fixed(m.referenceMilliseconds, 1)
            << " ms: more than **" << fixed(m.timeRatio, 1) << "x** its time.\n\n";
    }
    if (s.front) {
      const auto& f = *s.front;
      out << "Front: the reference at " << f.spp << " spp reaches " << fixed(f.referenceRegionPsnr, 2)
          << " dB over the blur region in " << fixed(f.referenceMilliseconds, 1) << " ms; ";
      if (f.label)
        out << "the fastest hybrid-rays case as close, " << *f.label << " (" << fixed(f.regionPsnr, 2) << " dB), in "
            << fixed(f.milliseconds, 1) << " ms: **" << fixed(f.timeRatio, 2) << "x** faster.\n\n";
      else
        out << "no hybrid-rays case is as close.\n\n";
    }
    out << "| case | median ms | frame PSNR dB | frame SSIM | region PSNR dB | region SSIM |\n"
        << "|---|---:|---:|---:|---:|---:|\n";
    for (const ErrorTimeCase& c : s.cases)
      out << "| " << c.label << " | " << fixed(c.frameMilliseconds.median, 1) << " | " << optionalText(c.framePsnr, 2)
          << " | " << optionalText(c.frameSsim, 4) << " | " << optionalText(c.regionPsnr, 2) << " | "
          << optionalText(c.regionSsim, 4) << " |\n";
  }
}

}  // namespace hmb::bench
