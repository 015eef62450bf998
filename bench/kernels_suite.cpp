#include "bench/kernels_suite.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <span>

#include <glm/glm.hpp>

#include "bench/floor_pass.h"
#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/scene.h"
#include "kernels/bvh/bvh_build_layout.h"
#include "kernels/shared/layer_layout.h"
#include "kernels/shared/scene_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/bvh_build_pass.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/passes/tile_max_pass.h"
#include "runtime/passes/trace_rays_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::bench {
namespace {

constexpr const char* kRaster = "raster";
constexpr const char* kBvhBuild = "bvh-build";
constexpr const char* kTrace = "trace";
constexpr const char* kTileMax = "tile-max";
constexpr const char* kGather = "gather";

// A generator seeded by the case's sizes alone, so an input does not depend on which other
// cases ran before it.
std::mt19937 caseRng(std::initializer_list<uint32_t> sizes) {
  std::vector<uint32_t> words{kKernelsSeed};
  words.insert(words.end(), sizes.begin(), sizes.end());
  std::seed_seq seed(words.begin(), words.end());
  return std::mt19937(seed);
}

// The device time of one timed run: the sum of its passes, each of them by name.
struct RunTime {
  double milliseconds = 0.0;
  std::vector<std::pair<std::string, double>> passes;
};

RunTime passSum(const vk::FrameTimings& timings) {
  RunTime run;
  for (const vk::PassTiming& pass : timings.passes) {
    if (!pass.milliseconds) throw Error("the device gave no timestamp for pass " + pass.name);
    run.milliseconds += *pass.milliseconds;
    run.passes.emplace_back(pass.name, *pass.milliseconds);
  }
  return run;
}

// Runs `run` warm-up + repeats times and fills the case's times and throughput from the timed runs.
void timeCase(KernelCase& c, const KernelsSuiteOptions& options, const std::function<RunTime()>& run) {
  std::vector<double> totals;
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> passTimes;
  const CpuSample cpuBefore = sampleCpu();
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    const RunTime time = run();
    if (i < options.warmup) continue;
    totals.push_back(time.milliseconds);
    // A pass that runs more than once in a run (none today) counts once, with its total.
    std::map<std::string, double> runPasses;
    for (const auto& [name, ms] : time.passes) {
      if (!passTimes.count(name) && !runPasses.count(name)) order.push_back(name);
      runPasses[name] += ms;
    }
    for (const auto& [name, ms] : runPasses) passTimes[name].push_back(ms);
  }
  // /proc counts CPU time in ticks of about 10 ms: over a shorter case the load would be mostly rounding.
  const CpuSample cpuAfter = sampleCpu();
  const double seconds = std::chrono::duration<double>(cpuAfter.wall - cpuBefore.wall).count();
  c.otherCpuLoad = seconds >= kMinLoadSeconds ? otherLoad(cpuBefore, cpuAfter) : NAN;
  c.milliseconds = summarize(totals);
  for (const std::string& name : order) c.passes.emplace_back(name, summarize(passTimes[name]));
  c.throughput = c.milliseconds.median > 0 ? double(c.items) / (c.milliseconds.median * 1e3) : 0.0;
}

// N random clip-space triangles, each vertex within kRasterTriangleRadiusPixels of a centre
// anywhere on the screen, at a random depth; one double-sided instance, so none is culled.
struct ClipSoup {
  std::vector<glm::vec4> clip;
  std::vector<gpu::GpuTriangle> triangles;
};

ClipSoup randomClipTriangles(uint32_t count, ImageSize size) {
  std::mt19937 rng = caseRng({size.width, size.height, count});
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-1.0f, 1.0f), depth(0.05f, 0.95f);
  ClipSoup soup;
  for (uint32_t t = 0; t < count; ++t) {
    const glm::vec2 centre(unit(rng) * float(size.width), unit(rng) * float(size.height));
    const float z = depth(rng);
    for (int v = 0; v < 3; ++v) {
      const glm::vec2 pixel = centre + kRasterTriangleRadiusPixels * glm::vec2(offset(rng), offset(rng));
      soup.clip.emplace_back(2.0f * pixel.x / float(size.width) - 1.0f, 2.0f * pixel.y / float(size.height) - 1.0f, z,
                             1.0f);
    }
    soup.triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2, 0u});
  }
  return soup;
}

KernelCase rasterCase(const vk::Context& context, ImageSize size, uint32_t count, const KernelsSuiteOptions& options) {
  const ClipSoup soup = randomClipTriangles(count, size);
  gpu::GpuInstance instance{};
  instance.flags = HMB_INSTANCE_DOUBLE_SIDED;
  const vk::Buffer clip = vk::uploadedBuffer(context, soup.clip, "bench clip positions");
  const vk::Buffer triangles = vk::uploadedBuffer(context, soup.triangles, "bench triangles");
  const vk::Buffer instances = vk::uploadedBuffer(context, std::vector{instance}, "bench instance");
  const vk::Buffer visibility(context, passes::RasterizePass::visibilityBytes(size.width, size.height),
                              vk::MemoryUse::Device, "bench visibility");
  passes::RasterizePass pass(context, passes::defaultVisibilityScheme(context));
  pass.reserve(count, size.width, size.height);
  const passes::RasterInputs inputs{&triangles, &instances, &clip, count};
  const auto record = [&](vk::FrameRecorder& f) { pass.record(f, inputs, visibility, size.width, size.height); };
  vk::FrameRecorder frame(context);
  passes::submitUntilRasterFits(frame, pass, record);  // sizes the setup and pair buffers, untimed

  KernelCase c;
  c.kernel = kRaster;
  c.width = size.width;
  c.height = size.height;
  c.triangles = count;
  c.items = count;
  c.unit = "Mtris/s";
  timeCase(c, options, [&] {
    frame.begin();
    record(frame);
    const vk::FrameTimings timings = frame.submitAndWait();
    if (pass.growIfOverflowed()) throw Error("raster: the rasterizer's buffers overflowed while timing");
    return passSum(timings);
  });
  const passes::RasterStats& stats = pass.stats();
  c.details = {{"visibility_scheme", passes::visibilitySchemeName(pass.scheme())},
               {"setup_triangles", stats.setupTriangles},
               {"tile_pairs", stats.tilePairs},
               {"large_triangles", stats.largeTriangles},
               {"clipped_triangles", stats.clippedTriangles}};
  return c;
}

// N random triangles in the unit cube, each within a box about the mean spacing across
// (N^-1/3), so neighbours overlap a little whatever N.
struct TriangleSoup {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
};

TriangleSoup randomTriangles(uint32_t count) {
  std::mt19937 rng = caseRng({count});
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), offset(-0.5f, 0.5f);
  const float spacing = std::cbrt(1.0f / float(std::max(count, 1u)));
  TriangleSoup soup;
  for (uint32_t t = 0; t < count; ++t) {
    const glm::vec3 centre(unit(rng), unit(rng), unit(rng));
    for (int v = 0; v < 3; ++v) {
      soup.positions.push_back(centre + spacing * glm::vec3(offset(rng), offset(rng), offset(rng)));
      soup.indices.push_back(3 * t + v);
    }
  }
  return soup;
}

KernelCase bvhBuildCase(const vk::Context& context, const TriangleSoup& soup, const KernelsSuiteOptions& options) {
  const auto count = static_cast<uint32_t>(soup.indices.size() / 3);
  // Boxes from the host: the time is the builder's alone (the bvh suite's adds the
  // triangle-bounds kernel).
  std::vector<gpu::BvhBox> boxes;
  for (uint32_t t = 0; t < count; ++t) {
    const glm::vec3 a = soup.positions[3 * t], b = soup.positions[3 * t + 1], d = soup.positions[3 * t + 2];
    boxes.push_back({glm::vec4(glm::min(a, glm::min(b, d)), 0.0f), glm::vec4(glm::max(a, glm::max(b, d)), 0.0f)});
  }
  const vk::Buffer boxBuffer = vk::uploadedBuffer(context, boxes, "bench triangle boxes");
  passes::BvhBuildPass builder(context, "bench BVH", HMB_BVH_MAX_LEAF);
  vk::FrameRecorder frame(context);
  const glm::uvec2 root(0u, count);

  KernelCase c;
  c.kernel = kBvhBuild;
  c.triangles = count;
  c.items = count;
  c.unit = "Mtris/s";
  timeCase(c, options, [&] {
    const passes::BvhBuildStats& stats = builder.build(frame, boxBuffer, count, std::span(&root, 1));
    // The builder keeps each submission's frame time, not its passes': the levels are summed.
    RunTime run;
    run.milliseconds = stats.deviceMilliseconds;
    double levels = 0.0;
    for (double ms : stats.levelMilliseconds) levels += ms;
    run.passes.emplace_back(passes::BvhBuildPass::kLevel, levels);
    return run;
  });
  const passes::BvhBuildStats& stats = builder.stats();
  c.details = {
      {"nodes", stats.nodes}, {"leaves", stats.leaves}, {"levels", stats.levels}, {"submissions", stats.submissions}};
  return c;
}

// Rays from random points in the unit cube (the soup's bounds) in random directions.
std::vector<gpu::TraceRay> randomRays(uint32_t count, uint32_t triangles) {
  std::mt19937 rng = caseRng({triangles, count});
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  std::vector<gpu::TraceRay> rays;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 origin(unit(rng), unit(rng), unit(rng));
    glm::vec3 direction(gauss(rng), gauss(rng), gauss(rng));
    if (glm::length(direction) == 0.0f) direction = glm::vec3(0.0f, 0.0f, 1.0f);
    rays.push_back({glm::vec4(origin, 0.0f),
                    glm::vec4(glm::normalize(direction), std::numeric_limits<float>::infinity()), 0u, HMB_IGNORE_NONE,
                    0u, 0u});
  }
  return rays;
}

KernelCase traceCase(const vk::Context& context, const TraceScene& scene, const passes::TraceRaysPass& pass,
                     uint32_t rayCount, const KernelsSuiteOptions& options) {
  const vk::Buffer rays = vk::uploadedBuffer(context, randomRays(rayCount, scene.triangleCount()), "bench rays");
  const vk::Buffer hits(context, std::max(rayCount, 1u) * sizeof(gpu::BvhHit), vk::MemoryUse::Device, "bench hits");
  vk::FrameRecorder frame(context);

  KernelCase c;
  c.kernel = kTrace;
  c.triangles = scene.triangleCount();
  c.rays = rayCount;
  c.items = rayCount;
  c.unit = "Mrays/s";
  timeCase(c, options, [&] {
    frame.begin();
    pass.record(frame, scene, rays, hits, rayCount);
    return passSum(frame.submitAndWait());
  });
  std::vector<gpu::BvhHit> found = hits.download<gpu::BvhHit>();
  found.resize(rayCount);
  const auto hitCount =
      std::count_if(found.begin(), found.end(), [](const gpu::BvhHit& h) { return h.triangle != HMB_NO_HIT; });
  c.details = {{"hits", hitCount}};
  return c;
}

// A G-buffer layer of random colours and depths, with velocities uniform in
// +-kMaxVelocityPixels, so every tile moves and the gather takes all its samples.
struct RandomLayer {
  vk::Buffer samples, surfaces, velocities;
  passes::MotionBlurInputs inputs;
};

RandomLayer randomLayer(const vk::Context& context, ImageSize size) {
  std::mt19937 rng = caseRng({size.width, size.height});
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), motion(-kMaxVelocityPixels, kMaxVelocityPixels);
  const size_t pixels = size_t(size.width) * size.height;
  std::vector<glm::uvec4> samples(pixels), surfaces(pixels);
  std::vector<glm::vec2> velocities(HMB_LAYER_VELOCITY_ENTRIES(pixels), glm::vec2(0.0f));
  for (size_t i = 0; i < pixels; ++i) {
    const glm::vec3 color(unit(rng), unit(rng), unit(rng));
    const float depth = 1.0f + 9.0f * unit(rng);
    const glm::vec2 velocity(motion(rng), motion(rng));
    samples[i] = gpu::packLayerSample(color, depth, velocity);
    surfaces[i] = gpu::packLayerSurface(glm::vec3(0.0f, 0.0f, 1.0f), 1u, depth, velocity);
    velocities[i] = gpu::layerVelocityEntry(velocity);
  }
  RandomLayer layer{vk::uploadedBuffer(context, samples, "bench samples"),
                    vk::uploadedBuffer(context, surfaces, "bench surfaces"),
                    vk::uploadedBuffer(context, velocities, "bench velocities"), {}};
  layer.inputs = {&layer.samples, &layer.surfaces, &layer.velocities, size.width, size.height};
  return layer;
}

// The floor pass (bench/floor_pass.h) at `size`, timed as the case is: each per-pixel kernel
// reports its time as a multiple of it (details: floor_ms, over_floor).
void addFloor(const vk::Context& context, ImageSize size, const KernelsSuiteOptions& options, KernelCase& c) {
  vk::FrameRecorder frame(context);
  const double median = summarize(FloorPass(context, size.width, size.height).time(frame, options.warmup, options.repeats)).median;
  c.details["floor_ms"] = median;
  c.details["over_floor"] = c.milliseconds.median / median;
}

KernelCase pixelCase(const std::string& kernel, ImageSize size) {
  KernelCase c;
  c.kernel = kernel;
  c.width = size.width;
  c.height = size.height;
  c.items = uint64_t(size.width) * size.height;
  c.unit = "Mpixels/s";
  return c;
}

KernelCase tileMaxCase(const vk::Context& context, ImageSize size, const KernelsSuiteOptions& options) {
  const RandomLayer layer = randomLayer(context, size);
  const passes::PostProcessSettings settings;  // the paper's defaults: m = 40
  const uint32_t tileSize = settings.effectiveTileSize();
  const passes::TileGrid grid = passes::tileGridFor(size.width, size.height, tileSize);
  const vk::Buffer tiles(context, std::max(grid.count(), 1u) * sizeof(glm::vec4), vk::MemoryUse::Device,
                         "bench tile max");
  const passes::TileMaxPass pass(context);
  vk::FrameRecorder frame(context);

  KernelCase c = pixelCase(kTileMax, size);
  timeCase(c, options, [&] {
    frame.begin();
    pass.record(frame, layer.velocities, tiles, size.width, size.height, tileSize, settings.velocityScale());
    return passSum(frame.submitAndWait());
  });
  c.details = {{"tile_size", tileSize}, {"tiles", grid.count()}};
  addFloor(context, size, options, c);
  return c;
}

KernelCase gatherCase(const vk::Context& context, ImageSize size, const KernelsSuiteOptions& options) {
  const RandomLayer layer = randomLayer(context, size);
  const passes::PostProcessSettings settings;  // the paper's defaults: 15 samples, m = 40, n = 3, adapted range
  passes::PostProcessStage stage(context, settings);
  stage.prepare(size.width, size.height);
  const vk::Buffer output(context, uint64_t(size.width) * size.height * sizeof(glm::vec4), vk::MemoryUse::Device,
                          "bench gather output");
  vk::FrameRecorder frame(context);
  frame.begin();
  stage.recordTiles(frame, layer.inputs);  // the neighbour-max tiles the gather reads, untimed
  frame.submitAndWait();

  const passes::GatherPass gather(context);
  KernelCase c = pixelCase(kGather, size);
  timeCase(c, options, [&] {
    frame.begin();
    gather.record(frame, layer.inputs, stage.neighborMax(), output, settings);
    return passSum(frame.submitAndWait());
  });
  c.details = {{"samples", settings.samples},
               {"tile_size", settings.effectiveTileSize()},
               {"neighborhood", settings.neighborhood},
               {"range", passes::rangeName(settings.effectiveRange())}};
  addFloor(context, size, options, c);
  return c;
}

std::string inputName(const KernelCase& c) {
  std::string name;
  const auto add = [&](const std::string& part) { name += (name.empty() ? "" : ", ") + part; };
  if (c.width) add(sizeName({c.width, c.height}));
  if (c.rays) add(std::to_string(c.rays) + " rays");
  if (c.triangles) add(std::to_string(c.triangles) + " triangles");
  return name;
}

}  // namespace

const std::vector<std::string>& kernelNames() {
  static const std::vector<std::string> names = {kRaster, kBvhBuild, kTrace, kTileMax, kGather};
  return names;
}

std::vector<KernelCase> runKernelsSuite(const vk::Context& context, const KernelsSuiteOptions& options,
                                        const Progress& progress) {
  if (!context.info().timestamps) throw Error("device " + context.info().name + " has no timestamps");
  if (options.repeats < 1) throw Error("kernels: repeats must be at least 1");
  if (options.kernels.empty()) throw Error("kernels: no kernels selected");
  for (const std::string& kernel : options.kernels)
    if (std::find(kernelNames().begin(), kernelNames().end(), kernel) == kernelNames().end())
      throw Error("kernels: '" + kernel + "' is not one of raster, bvh-build, trace, tile-max, gather");
  const auto selected = [&](const char* kernel) {
    return std::find(options.kernels.begin(), options.kernels.end(), kernel) != options.kernels.end();
  };
  if ((selected(kRaster) || selected(kTileMax) || selected(kGather)) && options.sizes.empty())
    throw Error("kernels: no image sizes");
  if ((selected(kRaster) || selected(kBvhBuild) || selected(kTrace)) && options.triangles.empty())
    throw Error("kernels: no triangle counts");
  if (selected(kTrace) && options.rays.empty()) throw Error("kernels: no ray counts");

  std::vector<KernelCase> cases;
  const auto done = [&](KernelCase c) {
    progress(c.kernel + " " + inputName(c) + ": " + fixed(c.milliseconds.median, 2) + " ms, " + fixed(c.throughput, 2) +
             " " + c.unit);
    cases.push_back(std::move(c));
  };
  if (selected(kRaster))
    for (const ImageSize size : options.sizes)
      for (const uint32_t count : options.triangles) done(rasterCase(context, size, count, options));
  if (selected(kBvhBuild) || selected(kTrace)) {
    const passes::TraceRaysPass tracePass(context);
    for (const uint32_t count : options.triangles) {
      const TriangleSoup soup = randomTriangles(count);
      if (selected(kBvhBuild)) done(bvhBuildCase(context, soup, options));
      if (!selected(kTrace)) continue;
      progress("trace: building the BVH over " + std::to_string(count) + " triangles");
      const scene::Scene scene = scene::singleMeshScene(soup.positions, soup.indices);
      vk::FrameRecorder frame(context);
      TraceScene traceScene(context, scene, frame);
      const float time = 0.0f;
      traceScene.setShutterTimes(scene, std::span(&time, 1), frame);
      for (const uint32_t rays : options.rays) done(traceCase(context, traceScene, tracePass, rays, options));
    }
  }
  if (selected(kTileMax))
    for (const ImageSize size : options.sizes) done(tileMaxCase(context, size, options));
  if (selected(kGather))
    for (const ImageSize size : options.sizes) done(gatherCase(context, size, options));
  return cases;
}

nlohmann::json kernelCaseJson(const KernelCase& c) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& [name, times] : c.passes) passes.push_back({{"name", name}, {"ms", summaryJson(times)}});
  const nlohmann::json otherCpuLoad =
      std::isnan(c.otherCpuLoad) ? nlohmann::json(nullptr) : nlohmann::json(c.otherCpuLoad);
  return {{"kernel", c.kernel},
          {"width", c.width},
          {"height", c.height},
          {"triangles", c.triangles},
          {"rays", c.rays},
          {"items", c.items},
          {"ms", summaryJson(c.milliseconds)},
          {"throughput", c.throughput},
          {"throughput_unit", c.unit},
          {"passes", passes},
          {"details", c.details},
          {"other_cpu_load_cores", otherCpuLoad}};
}

void writeKernelsCsv(std::ostream& out, const std::vector<KernelCase>& cases) {
  out << "kernel,width,height,triangles,rays,median_ms,q1_ms,q3_ms,min_ms,max_ms,throughput,throughput_unit,"
         "other_cpu_load_cores\n";
  for (const KernelCase& c : cases)
    out << c.kernel << ',' << c.width << ',' << c.height << ',' << c.triangles << ',' << c.rays << ','
        << c.milliseconds.median << ',' << c.milliseconds.q1 << ',' << c.milliseconds.q3 << ',' << c.milliseconds.min
        << ',' << c.milliseconds.max << ',' << c.throughput << ',' << c.unit << ',' << c.otherCpuLoad << '\n';
}

void writeKernelsMarkdown(std::ostream& out, const std::vector<KernelCase>& cases, const std::string& context) {
  out << context
      << "\n\n| kernel | input | median ms | interquartile ms | min - max ms | throughput | x floor | other cores busy |\n"
      << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const KernelCase& c : cases) {
    const Summary& t = c.milliseconds;
    const std::string overFloor = c.details.contains("over_floor") ? fixed(c.details["over_floor"].get<double>(), 1) : "-";
    out << "| " << c.kernel << " | " << inputName(c) << " | " << fixed(t.median, 2) << " | " << fixed(t.q1, 2) << " - "
        << fixed(t.q3, 2) << " | " << fixed(t.min, 2) << " - " << fixed(t.max, 2) << " | " << fixed(c.throughput, 2)
        << ' ' << c.unit << " | " << overFloor << " | " << (std::isnan(c.otherCpuLoad) ? "-" : fixed(c.otherCpuLoad, 2))
        << " |\n";
  }
  out << "\nx floor: the kernel's median over that of the floor pass at the same size (one 16-byte read and write "
         "per pixel, bench/floor_pass.h), timed in the same run.\n";
}

}  // namespace hmb::bench
