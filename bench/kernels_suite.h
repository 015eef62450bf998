// The `kernels` suite: single kernels on synthetic inputs of chosen sizes, for comparing devices
// and drivers. Each kernel runs through the runtime's own pass class, on inputs drawn from a
// fixed seed, so two machines time the same work:
//
//   raster     the compute rasterizer's visibility passes (RasterizePass: clears through
//              rasterize) over N random clip-space triangles of a few pixels each
//   bvh-build  the device SAH builder (BvhBuildPass) over the boxes of N random triangles
//   trace      the trace kernel (TraceRaysPass): random rays through the BVH over those triangles
//   tile-max   the post-process tile-max pass over a G-buffer of random velocities
//   gather     the post-process gather (McGuire, adapted range) over a random G-buffer
#pragma once

#include <cmath>
#include <cstdint>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

// The kernel names --kernels takes, in the order the suite runs them.
const std::vector<std::string>& kernelNames();

// Raster triangles: each vertex within this many pixels of the triangle's centre (mean area
// about 78 square pixels), centres anywhere on the screen.
constexpr float kRasterTriangleRadiusPixels = 16.0f;
// Synthetic G-buffer velocities: each component uniform in +-this many pixels per frame.
constexpr float kMaxVelocityPixels = 16.0f;
// Cases that run shorter than this get no other-process load (/proc's ticks are too coarse).
constexpr double kMinLoadSeconds = 1.0;
// Inputs are drawn from this seed: the same on every machine.
constexpr uint32_t kKernelsSeed = 1;

struct KernelsSuiteOptions {
  std::vector<ImageSize> sizes = {{640, 360}, {1280, 720}};
  std::vector<uint32_t> triangles = {10000, 100000};
  std::vector<uint32_t> rays = {262144};
  std::vector<std::string> kernels = kernelNames();
  int warmup = 1;
  int repeats = 5;
};

struct KernelCase {
  std::string kernel;
  // The input's sizes: those the kernel takes, 0 for the others.
  uint32_t width = 0, height = 0, triangles = 0, rays = 0;
  uint64_t items = 0;                                   // what the throughput counts: triangles, rays or pixels
  std::string unit;                                     // "Mtris/s", "Mrays/s" or "Mpixels/s"
  Summary milliseconds;                                 // the kernel's device time
  double throughput = 0.0;                              // items / median time, millions per second
  std::vector<std::pair<std::string, Summary>> passes;  // each pass in it, in dispatch order
  nlohmann::json details = nlohmann::json::object();    // what the kernel did (counters of the last run)
  // Cores busy with other processes while it ran; NaN without /proc or when it ran under
  // kMinLoadSeconds.
  double otherCpuLoad = NAN;
};

// Runs each selected kernel over its sizes: raster for every size and triangle count, bvh-build
// for every triangle count, trace for every triangle count and ray count, tile-max and gather
// for every size. Throws hmb::Error on an unknown kernel, an empty list or a device without
// timestamps.
std::vector<KernelCase> runKernelsSuite(const vk::Context& context, const KernelsSuiteOptions& options,
                                        const Progress& progress);

nlohmann::json kernelCaseJson(const KernelCase& c);
// One row per case: kernel, sizes, median, quartiles, min, max, throughput and its unit, other CPU load.
void writeKernelsCsv(std::ostream& out, const std::vector<KernelCase>& cases);
// `context` (device, settings, command) and then one table of every case.
void writeKernelsMarkdown(std::ostream& out, const std::vector<KernelCase>& cases, const std::string& context);

}  // namespace hmb::bench
