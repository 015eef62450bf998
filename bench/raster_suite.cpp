#include "bench/raster_suite.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <optional>
#include <span>
#include <sstream>

#include <glm/glm.hpp>

#include "bench/floor_pass.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "kernels/raster/raster_layout.h"
#include "kernels/shared/scene_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/oracle/graphics_gbuffer.h"
#include "tests/oracle/graphics_raster.h"

namespace hmb::bench {
std::string sizeName(ImageSize size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

std::string fixed(double value, int digits) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << value;
  return s.str();
}

CpuSample sampleCpu() {
  CpuSample sample;
  const double tick = 1.0 / double(sysconf(_SC_CLK_TCK));
  std::ifstream stat("/proc/stat");
  std::string label;
  unsigned long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  if (!(stat >> label >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal) || label != "cpu")
    return sample;
  sample.hostBusy = double(user + nice + system + irq + softirq + steal) * tick;
  // /proc/self/stat: utime and stime are fields 14 and 15, counted from the ')' closing the name.
  std::ifstream selfStat("/proc/self/stat");
  const std::string line((std::istreambuf_iterator<char>(selfStat)), std::istreambuf_iterator<char>());
  const auto close = line.rfind(')');
  if (close == std::string::npos) return sample;
  std::istringstream fields(line.substr(close + 2));
  std::string skip;
  for (int field = 3; field < 14; ++field) fields >> skip;
  unsigned long long utime = 0, stime = 0;
  if (!(fields >> utime >> stime)) return sample;
  sample.self = double(utime + stime) * tick;
  sample.valid = true;
  return sample;
}

double otherLoad(const CpuSample& from, const CpuSample& to) {
  const double wall = std::chrono::duration<double>(to.wall - from.wall).count();
  if (!from.valid || !to.valid || wall <= 0) return NAN;
  return std::max(0.0, ((to.hostBusy - from.hostBusy) - (to.self - from.self)) / wall);
}

namespace {

// Linear interpolation between order statistics (the common "type 7" quantile).
double required(const std::optional<double>& ms, const std::string& what) {
  if (!ms) throw Error(what + ": the device has no timestamps; the benchmark needs them");
  return *ms;
}

// The transform kernel's clip-space output with the scene's triangles, in triangle-id order, so
// equal depths resolve to the smallest id in both rasterizers. Sidedness comes from the device's
// instance flags: exactly what the compute rasterizer reads.
std::vector<oracle::OracleTriangle> oracleTriangles(const passes::GBufferStage& stage, const GpuScene& gpuScene) {
  std::vector<glm::vec4> clip = stage.clipCurrent().download<glm::vec4>();
  clip.resize(gpuScene.instanceVertexCount());
  std::vector<gpu::GpuTriangle> triangles = gpuScene.triangles().download<gpu::GpuTriangle>();
  triangles.resize(gpuScene.triangleCount());
  std::vector<bool> doubleSided;
  for (const gpu::GpuInstance& instance : gpuScene.instances().download<gpu::GpuInstance>())
    doubleSided.push_back((instance.flags & HMB_INSTANCE_DOUBLE_SIDED) != 0);
  return oracle::oracleTriangles(clip, triangles, doubleSided);
}

// The passes the graphics pipeline also does (clearing and rasterizing): everything in the
// G-buffer frame but transform (the oracle is handed clip-space vertices) and resolve (the
// oracle shades nothing). Defined by exclusion so that the sum stays right when the
// rasterizer's pass list changes.
bool isVisibilityPass(const std::string& name) {
  return name != passes::TransformVerticesPass::kName && name != passes::ResolveGBufferPass::kName;
}

RasterCase runCase(const vk::Context& context, const vk::Context& graphicsContext, const std::string& sceneName,
                   const scene::Scene& scene, ImageSize size, const RasterSuiteOptions& options,
                   const Progress& progress) {
  const std::string label = sceneName + " " + sizeName(size);
  GpuScene gpuScene(context, scene);
  gpuScene.setFrame(scene, scene.settings.frameTime, size.width, size.height);
  passes::GBufferStage stage(context, passes::defaultVisibilityScheme(context));
  stage.prepare(gpuScene, size.width, size.height);
  vk::FrameRecorder frame(context);
  const auto renderCompute = [&] {
    frame.begin();
    stage.record(frame, gpuScene);
    return frame.submitAndWait();
  };

  progress(label + ": sizing the rasterizer's buffers");
  try {
    passes::submitUntilRasterFits(frame, stage.rasterizer(), [&](vk::FrameRecorder& f) { stage.record(f, gpuScene); });
  } catch (const Error& e) {
    throw Error(label + ": " + e.what());
  }
  const std::vector<oracle::OracleTriangle> triangles = oracleTriangles(stage, gpuScene);
  oracle::GraphicsRasterizer graphics(graphicsContext, size.width, size.height);
  const FloorPass floor(context, size.width, size.height);
  // The G-buffer oracle draws on the graphics device, from the scene's buffers made there and
  // the transform kernel's output for this frame.
  GpuScene graphicsScene(graphicsContext, scene);
  graphicsScene.setFrame(scene, scene.settings.frameTime, size.width, size.height);
  if (gpuScene.texturePath()) graphicsScene.keepTexturePath();
  const auto firstVertices = [&](const vk::Buffer& buffer, auto element) {
    auto values = buffer.download<decltype(element)>();
    values.resize(gpuScene.instanceVertexCount());
    return values;
  };
  oracle::GraphicsGBuffer graphicsGBuffer(graphicsContext, graphicsScene, firstVertices(stage.clipCurrent(), glm::vec4()),
                                          firstVertices(stage.clipPrevious(), glm::vec4()),
                                          firstVertices(stage.vertexShading(), gpu::GpuVertexShading()), size.width,
                                          size.height);

  RasterCase result;
  result.scene = sceneName;
  result.size = size;
  result.visibilityScheme = passes::visibilitySchemeName(stage.rasterizer().scheme());
  result.triangles = gpuScene.triangleCount();

  std::vector<double> visibility, transform, resolve, computeFrame, graphicsDraw, ratio, floorMs;
  std::vector<double> computeGBuffer, graphicsGBufferMs, gbufferRatio;
  std::map<std::string, std::vector<double>> passSamples;
  progress(label + ": " + std::to_string(options.warmup) + " warm-up + " + std::to_string(options.repeats) +
           " timed iterations");
  const CpuSample cpuBefore = sampleCpu();
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    vk::FrameTimings compute;
    oracle::OracleImage image;
    oracle::GraphicsGBuffer::Image gbufferImage;
    double drawMs = 0, gbufferMs = 0;
    const auto runCompute = [&] {
      compute = renderCompute();
      if (stage.rasterizer().growIfOverflowed()) throw Error(label + ": rasterizer buffers overflowed during timing");
    };
    const auto runGraphics = [&] {
      image = graphics.rasterize(triangles);
      drawMs = required(graphics.lastDrawMilliseconds(), label);
      gbufferImage = graphicsGBuffer.render();
      gbufferMs = required(graphicsGBuffer.lastDrawMilliseconds(), label);
    };
    // Alternate which goes first, so neither always runs on caches the other warmed.
    if (i % 2 == 0) {
      runCompute();
      runGraphics();
    } else {
      runGraphics();
      runCompute();
    }

    // Validate while timing: every iteration, warm-up included.
    const auto requireAgreement = [&](const std::string& what, double share) {
      if (share < kMinIdAgreement)
        throw Error(label + ": " + what + " " + fixed(100.0 * share, 3) + "% is below " +
                    fixed(100.0 * kMinIdAgreement, 1) + "% (iteration " + std::to_string(i) + ")");
    };
    const double agreement = oracle::idAgreement(stage.visibility().download<glm::uvec2>(), image);
    requireAgreement("id agreement with the graphics pipeline", agreement);
    result.minIdAgreement = std::min(result.minIdAgreement, agreement);
    const oracle::GBufferAgreement gbuffer = oracle::compareGBuffers(
        stage.layer().samples().download<glm::uvec4>(), stage.layer().surfaces().download<glm::uvec4>(), gbufferImage);
    requireAgreement("object-id agreement with the G-buffer oracle", gbuffer.objectIds);
    result.minObjectAgreement = std::min(result.minObjectAgreement, gbuffer.objectIds);
    result.minAttributeAgreement = std::min(result.minAttributeAgreement, gbuffer.attributes);
    const double floorTime = floor.run(frame);
    if (i < options.warmup) continue;
    floorMs.push_back(floorTime);

    double vis = 0, resolveMs = 0;
    for (const vk::PassTiming& pass : compute.passes) {
      const double ms = required(pass.milliseconds, label);
      passSamples[pass.name].push_back(ms);
      if (pass.name == passes::TransformVerticesPass::kName)
        transform.push_back(ms);
      else if (pass.name == passes::ResolveGBufferPass::kName)
        resolveMs = ms;
      if (isVisibilityPass(pass.name)) vis += ms;
    }
    visibility.push_back(vis);
    resolve.push_back(resolveMs);
    computeGBuffer.push_back(vis + resolveMs);
    graphicsGBufferMs.push_back(gbufferMs);
    gbufferRatio.push_back(gbufferMs > 0 ? computeGBuffer.back() / gbufferMs : NAN);
    computeFrame.push_back(required(compute.frameMilliseconds, label));
    graphicsDraw.push_back(drawMs);
    ratio.push_back(drawMs > 0 ? vis / drawMs : NAN);
  }

  result.otherCpuLoad = otherLoad(cpuBefore, sampleCpu());
  const passes::RasterStats& stats = stage.rasterizer().stats();
  result.setupTriangles = stats.setupTriangles;
  result.tilePairs = stats.tilePairs;
  result.largeTriangles = stats.largeTriangles;
  result.regrowths = stats.regrowths;
  result.computeVisibility = summarize(visibility);
  result.transform = summarize(transform);
  result.resolve = summarize(resolve);
  result.computeFrame = summarize(computeFrame);
  result.graphicsDraw = summarize(graphicsDraw);
  result.floor = summarize(floorMs);
  result.computeGBuffer = summarize(computeGBuffer);
  result.graphicsGBuffer = summarize(graphicsGBufferMs);
  result.gbufferRatio = summarize(gbufferRatio);
  result.ratio = summarize(ratio);
  for (auto& [name, samples] : passSamples) result.passes[name] = summarize(samples);
  progress(label + ": visibility " + fixed(result.computeVisibility.median, 2) + " ms, graphics " +
           fixed(result.graphicsDraw.median, 2) + " ms, ratio " + fixed(result.ratio.median, 2) + "; G-buffer " +
           fixed(result.computeGBuffer.median, 2) + " ms, graphics " + fixed(result.graphicsGBuffer.median, 2) +
           " ms, ratio " + fixed(result.gbufferRatio.median, 2) + "; agreement " +
           fixed(100.0 * result.minIdAgreement, 3) + "%, other processes " + fixed(result.otherCpuLoad, 2) +
           " cores");
  return result;
}

}  // namespace

ImageSize parseImageSize(const std::string& text) {
  unsigned width = 0, height = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%ux%u%c", &width, &height, &tail) != 2 || width == 0 || height == 0)
    throw Error("image size '" + text + "' must be WIDTHxHEIGHT, e.g. 1280x720");
  return {width, height};
}

std::vector<RasterCase> runRasterSuite(const vk::Context& compute, const vk::Context& graphics,
                                       const RasterSuiteOptions& options, const Progress& progress) {
  if (!compute.info().timestamps) throw Error("device " + compute.info().name + " has no timestamps");
  if (compute.info().index != graphics.info().index)
    throw Error("the graphics context must use the same physical device as the compute context");
  std::vector<RasterCase> cases;
  for (const std::string& name : options.scenes) {
    progress("loading scene " + name);
    const scene::Scene scene = scene::loadScene(name);
    for (const ImageSize size : options.sizes)
      cases.push_back(runCase(compute, graphics, name, scene, size, options, progress));
  }
  return cases;
}

nlohmann::json rasterCaseJson(const RasterCase& c) {
  nlohmann::json passes = nlohmann::json::object();
  for (const auto& [name, summary] : c.passes) passes[name] = summaryJson(summary);
  return {
      {"scene", c.scene},
      {"width", c.size.width},
      {"height", c.size.height},
      {"visibility_scheme", c.visibilityScheme},
      {"triangles", c.triangles},
      {"setup_triangles", c.setupTriangles},
      {"tile_pairs", c.tilePairs},
      {"large_triangles", c.largeTriangles},
      {"regrowths", c.regrowths},
      {"min_id_agreement", c.minIdAgreement},
      {"other_cpu_load_cores", std::isnan(c.otherCpuLoad) ? nlohmann::json(nullptr) : nlohmann::json(c.otherCpuLoad)},
      {"ms",
       {{"compute_visibility", summaryJson(c.computeVisibility)},
        {"transform_vertices", summaryJson(c.transform)},
        {"resolve_gbuffer", summaryJson(c.resolve)},
        {"compute_frame", summaryJson(c.computeFrame)},
        {"graphics_draw", summaryJson(c.graphicsDraw)},
        {"floor", summaryJson(c.floor)},
        {"compute_gbuffer", summaryJson(c.computeGBuffer)},
        {"graphics_gbuffer", summaryJson(c.graphicsGBuffer)},
        {"compute_passes", passes}}},
      {"over_floor",
       {{"compute_visibility", c.computeVisibility.median / c.floor.median},
        {"resolve_gbuffer", c.resolve.median / c.floor.median},
        {"graphics_draw", c.graphicsDraw.median / c.floor.median},
        {"compute_gbuffer", c.computeGBuffer.median / c.floor.median},
        {"graphics_gbuffer", c.graphicsGBuffer.median / c.floor.median}}},
      {"ratio_visibility_to_graphics", summaryJson(c.ratio)},
      {"ratio_gbuffer_to_graphics_gbuffer", summaryJson(c.gbufferRatio)},
      {"gbuffer_oracle_agreement", {{"min_object_ids", c.minObjectAgreement}, {"min_attributes", c.minAttributeAgreement}}},
  };
}

void printRasterTable(std::ostream& out, const std::vector<RasterCase>& cases) {
  char line[320];
  std::snprintf(line, sizeof(line), "%-12s %-9s %8s %9s %6s %9s %8s %8s %8s %6s %17s %8s %8s %17s %9s %9s\n",
                "scene", "size", "tris", "pairs", "large", "transform", "visib.", "resolve", "graphics", "floor",
                "visib./graphics", "G-buffer", "gr. G-b.", "G-buf./graphics", "ids", "G-buffer");
  out << line;
  for (const RasterCase& c : cases) {
    const auto withRange = [](const Summary& r) {
      return fixed(r.median, 2) + " [" + fixed(r.q1, 2) + "-" + fixed(r.q3, 2) + "]";
    };
    std::snprintf(line, sizeof(line),
                  "%-12s %-9s %8u %9u %6u %9.2f %8.2f %8.2f %8.2f %6.2f %17s %8.2f %8.2f %17s %8.3f%% %8.3f%%\n",
                  c.scene.c_str(), sizeName(c.size).c_str(), c.triangles, c.tilePairs, c.largeTriangles,
                  c.transform.median, c.computeVisibility.median, c.resolve.median, c.graphicsDraw.median,
                  c.floor.median, withRange(c.ratio).c_str(), c.computeGBuffer.median, c.graphicsGBuffer.median,
                  withRange(c.gbufferRatio).c_str(), 100.0 * c.minIdAgreement, 100.0 * c.minAttributeAgreement);
    out << line;
  }
  out << "Times: device ms, medians. visib. = compute clears through rasterize (transform excluded: the graphics\n"
         "pipeline is given the same clip-space vertices); graphics = render pass clear + id draw + store.\n"
         "G-buffer = visib. + resolve; gr. G-b. = the graphics pipeline shading and packing the same G-buffer.\n"
         "Ratios: medians of per-iteration ratios [interquartile range]. ids: worst iteration's id agreement;\n"
         "G-buffer: worst iteration's share of pixels where depth, normal, velocity and colour agree.\n"
         "floor: one 16-byte read and write per pixel (bench/floor_pass.h), the least a full-screen pass costs.\n";
}

}  // namespace hmb::bench
