#include "runtime/cli/compare_command.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>

#include "hmblur/error.h"
#include "hmblur/report.h"
#include "runtime/cli/output_paths.h"
#include "runtime/io/image_files.h"
#include "runtime/metrics/metrics.h"

namespace hmb::cli {

namespace {

namespace fs = std::filesystem;

metrics::DisplayImage loadSized(const std::string& path, const metrics::DisplayImage* reference,
                                const std::string& referencePath) {
  metrics::DisplayImage image = metrics::loadDisplayImage(path);
  if (reference && (image.width != reference->width || image.height != reference->height))
    throw Error("'" + path + "' is " + metrics::sizeText(image.width, image.height) + " but the reference '" +
                referencePath + "' is " + metrics::sizeText(reference->width, reference->height));
  return image;
}

std::string formatted(const char* format, double value) {
  char text[32];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

std::string psnrText(double psnr) { return std::isfinite(psnr) ? formatted("%.2f", psnr) : "inf"; }
std::string ssimText(const std::optional<double>& ssim) { return ssim ? formatted("%.4f", *ssim) : "n/a"; }

std::string padded(const std::string& text, size_t width) {
  return text.size() >= width ? text + " " : text + std::string(width - text.size(), ' ');
}

// "<stem>-flip.png", numbered when two images share a stem.
fs::path errorImagePath(const fs::path& dir, const std::string& image, std::set<std::string>& taken) {
  const std::string stem = fs::path(image).stem().string();
  std::string name = stem + "-flip.png";
  for (int n = 2; taken.count(name); ++n) name = stem + "-flip-" + std::to_string(n) + ".png";
  taken.insert(name);
  return dir / name;
}

}  // namespace

CLI::App* addCompareCommand(CLI::App& app, CompareOptions& options) {
  CLI::App* command = app.add_subcommand(
      "compare", "PSNR, SSIM and FLIP of images against a reference, over the frame and the blur region");
  command->add_option("reference", options.reference, "Reference image (.png or .exr)")->required();
  command->add_option("images", options.images, "Images to measure (.png or .exr)")->required();
  command->add_option("--sharp", options.sharp,
                      "Sharp frame: the blur region is where the reference differs from it");
  command->add_option("--json", options.json, "JSON file for the metrics");
  command->add_option("--error-images", options.errorImagesDir, "Folder for a FLIP error image per image");
  command->add_option("--ppd", options.pixelsPerDegree, "FLIP pixels per degree of visual angle")
      ->capture_default_str();
  return command;
}

int runCompare(const CompareOptions& options) {
  prepareOutputFile(options.json, {".json"}, "--json");
  prepareOutputFolder(options.errorImagesDir, "--error-images");
  if (!(options.pixelsPerDegree > 0.0f) || !std::isfinite(options.pixelsPerDegree))
    throw Error("--ppd must be a positive number");
  metrics::MetricOptions metricOptions;
  metricOptions.pixelsPerDegree = options.pixelsPerDegree;

  const metrics::DisplayImage reference = metrics::loadDisplayImage(options.reference);
  std::optional<metrics::BlurRegion> region;
  if (!options.sharp.empty()) {
    const metrics::DisplayImage sharp = loadSized(options.sharp, &reference, options.reference);
    region = metrics::blurRegion(reference, sharp, metricOptions.blurRegionThreshold);
  }

  nlohmann::json report = {
      {"tool", "hmblur compare"},
      {"reference", options.reference},
      {"sharp", options.sharp.empty() ? nlohmann::json(nullptr) : nlohmann::json(options.sharp)},
      {"width", reference.width},
      {"height", reference.height},
      {"settings", metrics::metricsSettingsJson(metricOptions)},
      {"blur_region_pixels", region ? nlohmann::json(region->pixelCount) : nlohmann::json(nullptr)},
      {"images", nlohmann::json::array()}};

  // Every file is read before anything is printed, so a bad one fails with its error alone.
  std::vector<metrics::DisplayImage> images;
  for (const std::string& path : options.images) images.push_back(loadSized(path, &reference, options.reference));

  size_t nameWidth = 7;
  for (const std::string& path : options.images) nameWidth = std::max(nameWidth, path.size() + 2);
  const size_t frameColumns = 10 + 8 + 8;
  if (region) {
    const double fraction = double(region->pixelCount) / double(reference.pixelCount());
    std::cout << "blur region: " << region->pixelCount << " pixels (" << formatted("%.1f", 100.0 * fraction)
              << "% of the frame)\n";
    std::cout << padded("", nameWidth) << padded("frame", frameColumns) << "| blur region\n";
  }
  std::cout << padded("image", nameWidth) << padded("PSNR dB", 10) << padded("SSIM", 8) << padded("FLIP", 8);
  if (region) std::cout << "| " << padded("PSNR dB", 10) << padded("SSIM", 8) << "FLIP";
  std::cout << '\n';

  std::set<std::string> takenNames;
  for (size_t index = 0; index < images.size(); ++index) {
    const std::string& path = options.images[index];
    const metrics::Comparison comparison =
        metrics::compareImages(reference, images[index], region ? &*region : nullptr, metricOptions);

    nlohmann::json entry = {{"image", path}, {"metrics", metrics::metricsJson(comparison)}, {"error_image", nullptr}};
    if (!options.errorImagesDir.empty()) {
      const fs::path errorPath = errorImagePath(options.errorImagesDir, path, takenNames);
      io::writePng(errorPath, metrics::errorImage(comparison.flip));
      entry["error_image"] = errorPath.string();
    }
    report["images"].push_back(std::move(entry));

    const metrics::MetricValues& frame = comparison.frame;
    std::cout << padded(path, nameWidth) << padded(psnrText(frame.psnr), 10) << padded(ssimText(frame.ssim), 8)
              << padded(formatted("%.4f", frame.flip), 8);
    if (region) {
      std::cout << "| ";
      if (comparison.region)
        std::cout << padded(psnrText(comparison.region->psnr), 10) << padded(ssimText(comparison.region->ssim), 8)
                  << formatted("%.4f", comparison.region->flip);
      else
        std::cout << "empty";
    }
    std::cout << '\n';
  }
  if (!options.json.empty()) writeJson(options.json, report);
  return 0;
}

}  // namespace hmb::cli
