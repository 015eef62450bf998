#include "bench/explain_suite.h"
#include "bench/method_variants.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "bench/bench_scenes.h"
#include "hmblur/error.h"
#include "hmblur/method.h"
#include "hmblur/post_process_settings.h"
#include "hmblur/renderer.h"
#include "runtime/io/image_files.h"
#include "runtime/io/labelled_strip.h"
#include "runtime/metrics/metrics.h"
#include "runtime/metrics/screen_paths.h"

namespace fs = std::filesystem;

namespace hmb::bench {
namespace {

const std::vector<float>& beautyOf(const RenderResult& r) { return r.image.find("")->values; }

// The judge's images: the two halves and their mean, through the display transform.
struct Judge {
  metrics::DisplayImage image;
  std::vector<float> noise;
};

Judge renderJudge(Renderer& renderer, const scene::Scene& scene, const std::string& name,
                  const ExplainSuiteOptions& o, const Progress& progress) {
  std::vector<float> halves[2];
  for (uint32_t half = 0; half < 2; ++half) {
    RenderSettings settings;
    settings.method = Method::Reference;
    settings.width = o.size.width;
    settings.height = o.size.height;
    settings.reference.samplesPerPixel = o.referenceSpp / 2;
    settings.reference.seed = half + 1;
    settings.onProgress = [&](const passes::ReferenceProgress& p) {
      if (p.samplesDone == p.samplesTotal)
        progress(name + ": reference half " + std::to_string(half + 1) + ", " + std::to_string(p.samplesTotal) +
                 " spp");
    };
    halves[half] = beautyOf(renderer.render(scene, settings));
  }
  std::vector<float> mean(halves[0].size());
  for (size_t i = 0; i < mean.size(); ++i) mean[i] = 0.5f * (halves[0][i] + halves[1][i]);
  Judge judge;
  judge.image = metrics::displayImageFromLinearRgba(o.size.width, o.size.height, mean);
  judge.noise = metrics::referenceNoise(metrics::displayImageFromLinearRgba(o.size.width, o.size.height, halves[0]),
                                        metrics::displayImageFromLinearRgba(o.size.width, o.size.height, halves[1]));
  return judge;
}

io::Rgba8Image rgba8Of(const metrics::DisplayImage& image) {
  io::Rgba8Image out{.width = image.width, .height = image.height};
  out.pixels.resize(image.pixelCount() * 4);
  for (size_t i = 0; i < image.pixelCount(); ++i) {
    for (size_t c = 0; c < 3; ++c)
      out.pixels[4 * i + c] = static_cast<uint8_t>(std::lround(std::clamp(image.rgb[3 * i + c], 0.0f, 1.0f) * 255.0f));
    out.pixels[4 * i + 3] = 255;
  }
  return out;
}

// Each pixel's error as |difference| (mean over R, G, B) times 4, through the magma map.
io::Rgba8Image errorPanel(const metrics::DisplayImage& judge, const metrics::DisplayImage& image) {
  metrics::ScalarMap map{judge.width, judge.height, 0, std::vector<float>(judge.pixelCount())};
  for (size_t i = 0; i < map.values.size(); ++i) {
    float sum = 0.0f;
    for (size_t c = 0; c < 3; ++c) sum += std::abs(judge.rgb[3 * i + c] - image.rgb[3 * i + c]);
    map.values[i] = 4.0f * sum / 3.0f;
  }
  return metrics::errorImage(map);
}

std::string percent(double share, int digits = 1) { return fixed(100.0 * share, digits) + "%"; }

// The strip's caption: the two largest classes, a line each.
std::vector<std::string> sourcesCaption(const metrics::ErrorSources& sources) {
  std::vector<metrics::ErrorSourceRow> rows = sources.rows;
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.share > b.share; });
  std::vector<std::string> lines = {"where it comes from"};
  for (size_t k = 0; k < 2 && k < rows.size(); ++k)
    if (rows[k].share > 0.0)
      lines.push_back(std::string(metrics::errorSourceName(rows[k].source)) + " " + percent(rows[k].share));
  return lines;
}

}  // namespace

std::vector<ExplainCase> runExplainSuite(vk::Context& context, const ExplainSuiteOptions& o,
                                         const Progress& progress) {
  if (o.scenes.empty()) throw Error("explain: no scenes");
  if (o.timeSlices < 1 || o.timeSlices > passes::kMaxTimeSlices)
    throw Error("explain: time slices must be 1 to " + std::to_string(passes::kMaxTimeSlices));
  if (o.referenceSpp < 2 || o.referenceSpp % 2 != 0)
    throw Error("explain: the reference's samples per pixel must be even (two halves), at least 2");
  for (const std::string& method : o.methods) {
    RenderSettings check;
    applyMethodVariant(method, kExplainMethods, check);  // throws, naming them, for any other
  }
  if (!o.imageDir.empty()) fs::create_directories(o.imageDir);
  Renderer renderer(context);
  std::vector<ExplainCase> cases;
  for (const std::string& name : o.scenes) {
    const scene::Scene scene = loadBenchScene(name);
    RenderSettings settings;
    settings.width = o.size.width;
    settings.height = o.size.height;
    settings.method = Method::Sharp;
    progress(name + ": sharp frame and its paths");
    const RenderResult sharp = renderer.render(scene, settings);
    const std::vector<float>& depth = sharp.image.find("depth")->values;
    const ScreenPaths paths =
        screenPaths(scene, sharp.frameTime, o.size.width, o.size.height, depth, sharp.image.find("objectId")->ids);
    const Judge judge = renderJudge(renderer, scene, name, o, progress);
    const metrics::BlurRegion region =
        metrics::blurRegion(judge.image, metrics::displayImageFromRgba8(sharp.display));
    for (const std::string& method : o.methods) {
      progress(name + ": " + method);
      applyMethodVariant(method, kExplainMethods, settings);
      settings.postprocess.timeSlices = o.timeSlices;
      settings.postprocess.tileSize = o.tileSize;
      const RenderResult result = renderer.render(scene, settings);
      const metrics::DisplayImage image = metrics::displayImageFromRgba8(result.display);
      metrics::ErrorSourceInputs inputs;
      inputs.reference = &judge.image;
      inputs.test = &image;
      inputs.region = &region;
      inputs.pathLength = paths.length;
      inputs.pathBend = paths.bend;
      // Traced: revealed behind (the ray mask) or rendered by shutter rays.
      std::vector<uint32_t> traced;
      if (const io::ImageLayer* mask = result.image.find("rayMask")) traced = mask->ids;
      if (const io::ImageLayer* rays = result.image.find("shutterRays"))
        for (size_t i = 0; i < traced.size() && i < rays->ids.size(); ++i) traced[i] |= rays->ids[i];
      inputs.rayMask = traced;
      inputs.referenceNoise = judge.noise;
      ExplainCase c;
      c.scene = name;
      c.method = method;
      c.timeSlices = o.timeSlices;
      c.cameraMoves = paths.cameraMoves;
      c.sources = metrics::explainErrorSources(inputs);
      c.regionPixels = region.pixelCount;
      const std::optional<double> mse = metrics::meanSquaredError(judge.image, image, region);
      if (mse) c.regionPsnr = metrics::psnrFromMse(*mse);
      if (!o.imageDir.empty()) {
        const std::string psnr = !c.regionPsnr                   ? "empty"
                                 : std::isfinite(*c.regionPsnr) ? fixed(*c.regionPsnr, 2) + " dB"
                                                                : "exact";
        const io::LabelledStrip strip = io::labelledStrip({
            {rgba8Of(judge.image), {"reference", std::to_string(o.referenceSpp) + " spp"}},
            {rgba8Of(image), {o.timeSlices > 1 ? method + ", " + std::to_string(o.timeSlices) + " time slices" : method,
                              "blur region " + psnr}},
            {errorPanel(judge.image, image), {"error", "|difference| x4"}},
            {metrics::errorSourceImage(c.sources, judge.image), sourcesCaption(c.sources)},
        });
        c.strip = sceneStem(name) + "-" + method +
                  (o.timeSlices > 1 ? "-k" + std::to_string(o.timeSlices) : std::string()) + "-sources.png";
        io::writePng(fs::path(o.imageDir) / c.strip, strip.image);
      }
      cases.push_back(std::move(c));
    }
  }
  return cases;
}

nlohmann::json explainCaseJson(const ExplainCase& c) {
  nlohmann::json json = {{"scene", c.scene},
                         {"method", c.method},
                         {"time_slices", c.timeSlices},
                         {"region_pixels", c.regionPixels},
                         {"region_psnr_db", c.regionPsnr && std::isfinite(*c.regionPsnr) ? nlohmann::json(*c.regionPsnr)
                                                                                         : nlohmann::json(nullptr)},
                         {"camera_moves", c.cameraMoves},
                         {"sources", metrics::errorSourcesJson(c.sources)}};
  if (!c.strip.empty()) json["strip"] = c.strip;
  return json;
}

void writeExplainMarkdown(std::ostream& out, const std::vector<ExplainCase>& cases, const std::string& header) {
  out << header << "\n\n";
  out << "Share of each method's squared error over the blur region, by where it comes from "
         "(runtime/metrics/error_sources.h); in brackets, the reference's own noise as a share of the "
         "same error. Near: the window within which a moving or curved path counts, the image's longest "
         "path.\n\n";
  out << "| scene | method | region PSNR dB | camera moves | near (px) |";
  for (const metrics::ErrorSource s : metrics::kErrorSources) out << " " << metrics::errorSourceName(s) << " |";
  out << " noise | strip |\n|---|---|---:|---|---:|";
  for (size_t k = 0; k < metrics::kErrorSources.size(); ++k) out << "---:|";
  out << "---:|---|\n";
  for (const ExplainCase& c : cases) {
    const metrics::ErrorSources& s = c.sources;
    out << "| " << c.scene << " | " << c.method << " | " << (c.regionPsnr ? fixed(*c.regionPsnr, 2) : "-") << " | "
        << (c.cameraMoves ? "yes" : "no") << " | " << s.reachPixels << " |";
    for (const metrics::ErrorSourceRow& row : s.rows) {
      out << " " << percent(row.share);
      if (row.noise && s.squaredError > 0.0) out << " (" << percent(*row.noise / s.squaredError, 3) << ")";
      out << " |";
    }
    out << " " << (s.noise && s.squaredError > 0.0 ? percent(*s.noise / s.squaredError, 3) : "-") << " | "
        << (c.strip.empty() ? "-" : "[" + c.strip + "](" + c.strip + ")") << " |\n";
  }
  out << "\nPixels per class:\n\n| scene | method |";
  for (const metrics::ErrorSource s : metrics::kErrorSources) out << " " << metrics::errorSourceName(s) << " |";
  out << "\n|---|---|";
  for (size_t k = 0; k < metrics::kErrorSources.size(); ++k) out << "---:|";
  out << "\n";
  for (const ExplainCase& c : cases) {
    out << "| " << c.scene << " | " << c.method << " |";
    for (const metrics::ErrorSourceRow& row : c.sources.rows) out << " " << row.pixels << " |";
    out << "\n";
  }
}

}  // namespace hmb::bench
