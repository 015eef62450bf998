// The `error-vs-time` suite: for each scene, every method at a range of settings (sharp;
// post-process, centred and adapted, at several sample counts; hybrid at several sample
// counts and shutter strata, and without its shutter rays (the paper's) at several
// reveal-recursion limits and edge thresholds; both with the shutter cut into 2, 3
// and 4 time slices; the reference at 1, 2, 4 ... spp), its
// median frame time (device timestamps) and its error against a high-spp judge (PSNR and SSIM
// over the frame and the blur region). Where hybrid sits on the reference's spp curve is the
// headline: the fewest spp whose blur-region PSNR reaches hybrid's, and that render's time over
// hybrid's.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"
#include "hmblur/renderer.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

struct ErrorTimeSuiteOptions {
  std::vector<std::string> scenes;  // reference scene names or glTF paths
  ImageSize size{1280, 720};
  // Judges: DIR/SCENE-reference.exr when given (a glTF file's SCENE is its file stem), else
  // rendered here at judgeSpp (seed 1, pixel centres).
  std::string referenceDir;
  uint32_t judgeSpp = 1024;
  std::vector<uint32_t> samples = {5, 9, 15, 23, 31};  // post-process and hybrid gather samples
  std::vector<uint32_t> recursionLimits = {1, 5};      // the paper's hybrid, luminance stop
  std::vector<float> edgeThresholds = {0.5f, 0.8f, 0.95f};  // the paper's hybrid (the scene's own: its samples series)
  std::vector<uint32_t> timeSlices = {2, 3, 4};              // adapted post-process and hybrid, the shutter cut in K
  std::vector<uint32_t> shutterRays = {2, 4, 16};            // hybrid-rays' strata (its default, 8, is in its samples series)
  // hybrid-rays' ray budgets, in rays per pixel of the image (--ray-budget of that many times
  // width x height): its curve from post-process towards every listed pixel's rays.
  std::vector<double> rayBudgets = {0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5};
  // The reference the front is held against: the fastest hybrid-rays case whose blur-region
  // error is the reference's at this many spp, and its time over the reference's.
  uint32_t frontSpp = 4;
  std::vector<uint32_t> referenceSpp = {1, 2, 4, 8, 16, 32, 64, 128, 256};  // seed 2: not the judge's strata
  int warmup = 1;
  int repeats = 3;
  int referenceRepeats = 1;  // reference renders take seconds to minutes: timer noise is small there
};

struct ErrorTimeCase {
  std::string scene;
  std::string method;  // sharp | postprocess | hybrid | reference
  std::string label;   // e.g. "postprocess adapted S15", "reference 64 spp"
  std::string series;  // the curve it belongs to in the plot
  double parameter = 0;  // the series' varying value (samples, spp, recursion, threshold)
  Summary frameMilliseconds;
  double framePsnr = 0, frameSsim = 0;
  std::optional<double> regionPsnr, regionSsim;
  uint64_t maskPixels = 0, revealRays = 0;  // hybrid
  uint64_t shutterRays = 0;                 // hybrid-rays: rays traced
};

struct ErrorTimeScene {
  std::string scene;
  std::string judge;  // where the judge came from
  size_t regionPixels = 0;
  std::vector<ErrorTimeCase> cases;
  // Each hybrid method at its defaults against the reference's spp curve.
  struct Match {
    std::string method;  // hybrid | hybrid-rays
    double hybridRegionPsnr = 0, hybridMilliseconds = 0;
    std::optional<uint32_t> spp;  // fewest spp reaching hybrid's blur-region PSNR; absent: none tried
    double referenceMilliseconds = 0;  // that render's time (or the largest spp's, when none)
    double timeRatio = 0;              // referenceMilliseconds / hybridMilliseconds
  };
  std::vector<Match> matches;
  // The front: the reference at frontSpp, and the fastest hybrid-rays case (any series) at
  // least as close to the judge over the blur region.
  struct Front {
    uint32_t spp = 0;
    double referenceRegionPsnr = 0, referenceMilliseconds = 0;
    std::optional<std::string> label;  // absent: no hybrid-rays case reaches it
    double regionPsnr = 0, milliseconds = 0;
    double timeRatio = 0;  // referenceMilliseconds / milliseconds
  };
  std::optional<Front> front;
};

std::vector<ErrorTimeScene> runErrorTimeSuite(vk::Context& context, const ErrorTimeSuiteOptions& options,
                                              const Progress& progress);

nlohmann::json errorTimeSceneJson(const ErrorTimeScene& s);
// One row per case: scene, method, label, series, parameter, median ms, PSNR/SSIM frame and region.
void writeErrorTimeCsv(std::ostream& out, const std::vector<ErrorTimeScene>& scenes);
// Per scene: the match line, then a table of every case.
void writeErrorTimeMarkdown(std::ostream& out, const std::vector<ErrorTimeScene>& scenes, const std::string& context);

}  // namespace hmb::bench
