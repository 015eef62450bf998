// The `raster` suite: the compute rasterizer (G-buffer stage) against lavapipe's own graphics
// pipeline (the test oracles) on the same clip-space triangles, same device, same run: the
// visibility passes against a depth-tested draw of triangle ids, and the whole G-buffer
// (visibility and resolve) against a draw whose fragments shade and pack the same layer. Compute
// and graphics iterations alternate in one loop, so drift hits both alike; every iteration
// also checks that both saw the same triangle per pixel (a fast wrong rasterizer is no result).
//
// The two sides run on two logical devices of the same physical device. On lavapipe a
// render pass leaves its framebuffer bound to the queue's context, and from then on timestamps
// are binned into the rasterizer's scene and written at its next flush, after the compute work
// they should bracket: per-pass times collapse to ~0 while the frame total stays right. A
// compute queue that never draws keeps exact per-pass times.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/sample_summary.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

// Below this fraction of pixels with the same triangle id the run fails: timing a rasterizer
// that disagrees with the oracle would compare different work.
constexpr double kMinIdAgreement = 0.995;

// Above this many cores busy with other processes during a case, the driver warns.
constexpr double kMaxOtherCpuLoad = 0.1;

// Busy CPU seconds of the whole host and of this process (lavapipe's threads included), from
// /proc; valid is false where /proc is missing.
struct CpuSample {
  double hostBusy = 0, self = 0;
  std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  bool valid = false;
};

CpuSample sampleCpu();
// Cores busy with other processes between two samples (NaN without /proc). On a CPU device
// anything else running competes with the kernels and slows them.
double otherLoad(const CpuSample& from, const CpuSample& to);

struct ImageSize {
  uint32_t width = 0, height = 0;
};

// "1280x720" -> {1280, 720}; throws hmb::Error on anything else.
ImageSize parseImageSize(const std::string& text);
// {1280, 720} -> "1280x720".
std::string sizeName(ImageSize size);

// A number with `digits` decimals, for the suites' tables.
std::string fixed(double value, int digits);

struct RasterSuiteOptions {
  std::vector<std::string> scenes;  // reference scene names or glTF paths
  std::vector<ImageSize> sizes;
  int warmup = 3;
  int repeats = 15;
};

struct RasterCase {
  std::string scene;
  ImageSize size;
  std::string visibilityScheme;
  // What the rasterizer did (the last timed frame's counters).
  uint32_t triangles = 0, setupTriangles = 0, tilePairs = 0, largeTriangles = 0, regrowths = 0;
  // Device milliseconds.
  Summary computeVisibility;  // clears through rasterize: the work the graphics pipeline also does
  Summary transform;          // transform-vertices (the oracle gets clip-space vertices for free)
  Summary resolve;            // resolve-gbuffer
  Summary computeFrame;       // the whole G-buffer frame, first pass start to last pass end
  Summary graphicsDraw;       // the oracle's render pass: clear, draws, store
  Summary floor;              // the floor pass (bench/floor_pass.h) at this size: every pass's yardstick
  // The whole G-buffer: compute visibility + resolve against the graphics pipeline doing the same
  // job (the G-buffer oracle, tests/oracle/graphics_gbuffer.h), paired per iteration.
  Summary computeGBuffer, graphicsGBuffer, gbufferRatio;
  double minObjectAgreement = 1.0, minAttributeAgreement = 1.0;  // worst iteration
  Summary ratio;              // computeVisibility / graphicsDraw, paired per iteration
  std::map<std::string, Summary> passes;  // every compute pass by name
  double minIdAgreement = 1.0;            // worst iteration
  // Cores busy with other processes, averaged over the case (Linux /proc; NaN elsewhere). On a
  // CPU device anything else running competes with both rasterizers and skews the ratio.
  double otherCpuLoad = NAN;
};

using Progress = std::function<void(const std::string&)>;

// Runs every scene at every size: the G-buffer stage on `compute`, the graphics pipeline on
// `graphics` (a second context on the same physical device). Throws hmb::Error when agreement
// falls below kMinIdAgreement, the two contexts are different devices, or there are no timestamps.
std::vector<RasterCase> runRasterSuite(const vk::Context& compute, const vk::Context& graphics,
                                       const RasterSuiteOptions& options, const Progress& progress);

nlohmann::json rasterCaseJson(const RasterCase& c);

// The human-readable table (medians; ratio with its interquartile range).
void printRasterTable(std::ostream& out, const std::vector<RasterCase>& cases);

}  // namespace hmb::bench
