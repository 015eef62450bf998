// The `explain` suite: where each method's blur-region error against the reference comes from
// (runtime/metrics/error_sources.h). Per scene it renders the sharp frame (its depth and object
// ids give every pixel's path over the shutter, runtime/metrics/screen_paths.h), post-process and
// hybrid at their defaults, and the reference as two independent halves (seeds 1 and 2),
// whose mean is the judge and whose difference is the judge's own noise. Per method it writes
// a labelled strip (reference, method, error, classes) and a table of each class's share of
// the squared error. With time slices the classes still come from the whole shutter's paths
// and the ray mask is the last slice's.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"
#include "runtime/metrics/error_sources.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

// The methods it explains (bench/method_variants.h: the -curved ones along curved paths).
inline const std::vector<std::string> kExplainMethods = {"postprocess", "postprocess-curved", "hybrid", "hybrid-curved",
                                                         "hybrid-rays", "hybrid-rays-curved"};

struct ExplainSuiteOptions {
  std::vector<std::string> scenes;  // reference scene names or glTF paths
  ImageSize size{320, 180};
  uint32_t referenceSpp = 256;  // both halves together
  std::vector<std::string> methods = {"postprocess", "hybrid"};
  uint32_t timeSlices = 1;  // the methods' time slices (RenderSettings: postprocess.timeSlices)
  std::optional<uint32_t> tileSize;  // every method's; unset: their defaults
  std::string imageDir;  // where the strips go; empty: none
};

struct ExplainCase {
  std::string scene;
  std::string method;
  uint32_t timeSlices = 1;
  std::optional<double> regionPsnr;  // against the judge; none when the region is empty
  size_t regionPixels = 0;
  bool cameraMoves = false;
  metrics::ErrorSources sources;
  std::string strip;  // the strip's file name, empty when none was written
};

std::vector<ExplainCase> runExplainSuite(vk::Context& context, const ExplainSuiteOptions& options,
                                         const Progress& progress);

nlohmann::json explainCaseJson(const ExplainCase& c);
void writeExplainMarkdown(std::ostream& out, const std::vector<ExplainCase>& cases, const std::string& header);

}  // namespace hmb::bench
