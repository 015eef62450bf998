// The `passes` suite: per-pass device time of each method on each scene at several image
// sizes, to show how each pass's cost grows with pixels, triangles and the ray mask, and each
// render's device memory: its peak, the G-buffer's bytes per pixel and (hybrid) the mesh
// trees' bytes per triangle, as allocated for the worst case and as built. The methods of a
// scene and size are rendered in turn, a round at a time, so their frames compare as ratios.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

// The methods it times (bench/method_variants.h: the -curved ones along curved paths).
inline const std::vector<std::string> kPassesMethods = {"sharp",       "postprocess", "postprocess-curved",
                                                        "hybrid",      "hybrid-curved", "hybrid-rays",
                                                        "hybrid-rays-curved"};

struct PassesSuiteOptions {
  std::vector<std::string> scenes;  // reference scene names or glTF paths
  std::vector<ImageSize> sizes = {{640, 360}, {1280, 720}, {1920, 1080}};
  std::vector<std::string> methods = {"sharp", "postprocess", "hybrid", "hybrid-rays"};
  int warmup = 1;
  int repeats = 3;
};

struct PassesCase {
  std::string scene, method;
  ImageSize size;
  uint64_t triangles = 0;
  Summary frameMilliseconds;  // scene setup (the hybrid's mesh trees) left out
  Summary floor;              // the floor pass at this size (bench/floor_pass.h), timed before the size's renders
  // Each round's frame over post-process's of the same round, where post-process is among the
  // methods: the ratio a drifting machine moves least.
  std::optional<Summary> frameOverPostprocess;
  std::vector<std::pair<std::string, Summary>> passes;  // in plan order; skipped passes absent
  std::vector<std::pair<std::string, std::string>> skipped;  // name, reason
  uint64_t peakBytes = 0;
  double gbufferBytesPerPixel = 0;
  std::optional<double> bvhAllocatedBytesPerTriangle, bvhBuiltBytesPerTriangle;
  uint64_t maskPixels = 0, revealRays = 0;  // hybrid
  vk::FrameShape shape;  // the last timed frame's dispatches, barriers, host waits and chain
};

std::vector<PassesCase> runPassesSuite(vk::Context& context, const PassesSuiteOptions& options,
                                       const Progress& progress);

nlohmann::json passesCaseJson(const PassesCase& c);
// One row per case and pass: scene, method, width, height, pass, median ms, q1, q3.
void writePassesCsv(std::ostream& out, const std::vector<PassesCase>& cases);
// A summary table (frame time, its ratio to post-process's and memory per case), then per
// scene a table of passes by case.
void writePassesMarkdown(std::ostream& out, const std::vector<PassesCase>& cases, const std::string& context);

}  // namespace hmb::bench
