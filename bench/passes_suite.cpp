#include "bench/method_variants.h"
#include "bench/passes_suite.h"

#include <algorithm>
#include <map>
#include <memory>

#include "bench/bench_scenes.h"
#include "bench/floor_pass.h"
#include "hmblur/error.h"
#include "hmblur/renderer.h"
#include "hmblur/report.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::bench {
namespace {

double mib(uint64_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

// The floor pass at `size`: warm-up and repeats as the case's. Its buffers are gone before the
// case renders, so they do not count in the case's device memory.
Summary timeFloor(const vk::Context& context, const ImageSize& size, const PassesSuiteOptions& o) {
  vk::FrameRecorder frame(context);
  return summarize(FloorPass(context, size.width, size.height).time(frame, o.warmup, o.repeats));
}

// One method's renders at one size, interleaved with the other methods' (runPassesSuite).
struct MethodRuns {
  std::string method;
  RenderSettings settings;
  std::unique_ptr<Renderer> renderer;
  std::vector<double> frames;
  std::map<std::string, std::vector<double>> passTimes;
  std::vector<std::string> order;
  RenderResult last;
  uint64_t peakBytes = 0;
};

void renderOnce(const scene::Scene& scene, MethodRuns& runs, bool timed) {
  runs.last = runs.renderer->render(scene, runs.settings);
  if (!runs.last.frameMilliseconds) throw Error("the device gives no timestamps: pass times cannot be measured");
  if (!timed) return;
  // The hybrid's scene setup (its mesh trees, its still instances' tree) is listed as passes
  // but not counted in its frame.
  for (const PlannedPass& pass : runs.last.plan.passes()) {
    if (!pass.run || !pass.milliseconds) continue;
    if (!runs.passTimes.count(pass.name)) runs.order.push_back(pass.name);
    runs.passTimes[pass.name].push_back(*pass.milliseconds);
  }
  runs.frames.push_back(*runs.last.frameMilliseconds);
}

PassesCase caseOf(const MethodRuns& runs, const scene::Scene& scene, const std::string& name, const ImageSize& size,
                  const Summary& floor) {
  PassesCase c;
  c.scene = name;
  c.method = runs.method;
  c.size = size;
  c.triangles = scene.triangleCount();
  c.frameMilliseconds = summarize(runs.frames);  // setup left out, as the renderer reports it
  c.floor = floor;
  for (const std::string& pass : runs.order) c.passes.emplace_back(pass, summarize(runs.passTimes.at(pass)));
  for (const PlannedPass& pass : runs.last.plan.passes())
    if (!pass.run) c.skipped.emplace_back(pass.name, pass.reason);
  c.peakBytes = runs.peakBytes;
  c.shape = runs.last.frameShape;
  c.gbufferBytesPerPixel = runs.last.memory.gbufferBytesPerPixel;
  c.bvhAllocatedBytesPerTriangle = runs.last.memory.bvhAllocatedBytesPerTriangle;
  c.bvhBuiltBytesPerTriangle = runs.last.memory.bvhBuiltBytesPerTriangle;
  if (runs.last.hybrid) {
    c.maskPixels = runs.last.hybrid->maskPixels;
    c.revealRays = runs.last.hybrid->revealRays;
  }
  return c;
}

// The methods of one scene and size, rendered in rounds (each method once a round, in the
// order given), so that every method sees the machine as it is during the same seconds: a
// machine whose speed drifts moves all of a round's frames together, and the per-round ratio
// to post-process's frame (frameOverPostprocess) cancels it.
std::vector<PassesCase> runSize(vk::Context& context, const scene::Scene& scene, const std::string& name,
                                const ImageSize& size, const PassesSuiteOptions& o) {
  const Summary floor = timeFloor(context, size, o);
  std::vector<MethodRuns> runs(o.methods.size());
  for (size_t m = 0; m < o.methods.size(); ++m) {
    MethodRuns& r = runs[m];
    r.method = o.methods[m];
    applyMethodVariant(r.method, kPassesMethods, r.settings);
    r.settings.width = size.width;
    r.settings.height = size.height;
    r.settings.reuseAcrossFrames = false;  // each repeat is timed as a new frame: nothing kept from the last one
    // A renderer per method, its first render made while the others hold what they hold: its
    // peak less that is what this method needs.
    const uint64_t othersHold = context.memoryInUse();
    r.renderer = std::make_unique<Renderer>(context);
    renderOnce(scene, r, o.warmup == 0);
    r.peakBytes = r.last.memory.peakBytes - std::min(othersHold, r.last.memory.peakBytes);
    for (int i = 1; i < o.warmup; ++i) renderOnce(scene, r, false);
  }
  for (int round = o.warmup == 0 ? 1 : 0; round < o.repeats; ++round)
    for (MethodRuns& r : runs) renderOnce(scene, r, true);

  std::vector<PassesCase> cases;
  const auto postprocess = std::find_if(runs.begin(), runs.end(), [](const MethodRuns& r) { return r.method == "postprocess"; });
  for (const MethodRuns& r : runs) {
    cases.push_back(caseOf(r, scene, name, size, floor));
    if (postprocess == runs.end()) continue;
    std::vector<double> ratios;
    for (size_t i = 0; i < r.frames.size(); ++i) ratios.push_back(r.frames[i] / postprocess->frames[i]);
    cases.back().frameOverPostprocess = summarize(ratios);
  }
  return cases;
}

}  // namespace

std::vector<PassesCase> runPassesSuite(vk::Context& context, const PassesSuiteOptions& options,
                                       const Progress& progress) {
  if (options.repeats < 1) throw Error("passes: repeats must be at least 1");
  if (options.scenes.empty() || options.sizes.empty() || options.methods.empty())
    throw Error("passes: no scenes, sizes or methods");
  for (const std::string& method : options.methods) {
    RenderSettings check;
    applyMethodVariant(method, kPassesMethods, check);  // throws, naming them, for any other
  }
  std::vector<PassesCase> cases;
  for (const std::string& name : options.scenes) {
    const scene::Scene scene = loadBenchScene(name);
    for (const ImageSize& size : options.sizes) {
      progress(name + " " + sizeName(size));
      for (PassesCase& c : runSize(context, scene, name, size, options)) cases.push_back(std::move(c));
    }
  }
  return cases;
}

nlohmann::json passesCaseJson(const PassesCase& c) {
  nlohmann::json passes = nlohmann::json::array(), skipped = nlohmann::json::array();
  for (const auto& [name, times] : c.passes)
    passes.push_back({{"name", name}, {"ms", summaryJson(times)}, {"over_floor", times.median / c.floor.median}});
  for (const auto& [name, reason] : c.skipped) skipped.push_back({{"name", name}, {"reason", reason}});
  return {{"scene", c.scene},
          {"method", c.method},
          {"width", c.size.width},
          {"height", c.size.height},
          {"triangles", c.triangles},
          {"frame_ms", summaryJson(c.frameMilliseconds)},
          {"frame", frameShapeJson(c.shape)},
          {"frame_over_postprocess", c.frameOverPostprocess ? summaryJson(*c.frameOverPostprocess) : nlohmann::json()},
          {"floor_ms", summaryJson(c.floor)},
          {"passes", passes},
          {"skipped", skipped},
          {"device_memory",
           {{"peak_bytes", c.peakBytes},
            {"gbuffer_bytes_per_pixel", c.gbufferBytesPerPixel},
            {"bvh_allocated_bytes_per_triangle", optionalNumber(c.bvhAllocatedBytesPerTriangle)},
            {"bvh_built_bytes_per_triangle", optionalNumber(c.bvhBuiltBytesPerTriangle)}}},
          {"mask_pixels", c.maskPixels},
          {"reveal_rays", c.revealRays}};
}

void writePassesCsv(std::ostream& out, const std::vector<PassesCase>& cases) {
  out << "scene,method,width,height,pass,median_ms,q1_ms,q3_ms,over_floor\n";
  for (const PassesCase& c : cases) {
    const auto row = [&](const std::string& name, const Summary& t) {
      out << c.scene << ',' << c.method << ',' << c.size.width << ',' << c.size.height << ',' << name << ','
          << t.median << ',' << t.q1 << ',' << t.q3 << ',' << t.median / c.floor.median << '\n';
    };
    row("frame", c.frameMilliseconds);
    row(FloorPass::kName, c.floor);
    for (const auto& [name, t] : c.passes) row(name, t);
  }
}

void writePassesMarkdown(std::ostream& out, const std::vector<PassesCase>& cases, const std::string& context) {
  out << context << "\n\n";
  out << "| scene | size | method | frame ms | x post-process (per round) | dispatches (indirect) | barriers | "
         "host waits | dependent chain | peak device MiB | G-buffer B/pixel "
         "| BVH B/triangle (allocated / built) | mask pixels | reveal rays |\n"
         "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const PassesCase& c : cases) {
    const std::string bvh = c.bvhAllocatedBytesPerTriangle
                                ? fixed(*c.bvhAllocatedBytesPerTriangle, 1) + " / " + fixed(*c.bvhBuiltBytesPerTriangle, 1)
                                : "-";
    out << "| " << c.scene << " | " << sizeName(c.size) << " | " << c.method << " | "
        << fixed(c.frameMilliseconds.median, 1) << " | "
        << (c.frameOverPostprocess ? fixed(c.frameOverPostprocess->median, 3) : std::string("-")) << " | "
        << c.shape.dispatches << " (" << c.shape.indirectDispatches << ") | " << c.shape.barriers << " | "
        << c.shape.hostWaits << " | " << c.shape.dependentChain << " | " << fixed(mib(c.peakBytes), 1) << " | "
        << fixed(c.gbufferBytesPerPixel, 0) << " | " << bvh << " | " << c.maskPixels << " | " << c.revealRays << " |\n";
  }
  std::vector<std::string> scenes;
  for (const PassesCase& c : cases)
    if (std::find(scenes.begin(), scenes.end(), c.scene) == scenes.end()) scenes.push_back(c.scene);
  for (const std::string& scene : scenes) {
    std::vector<const PassesCase*> columns;
    std::vector<std::string> rows;
    for (const PassesCase& c : cases) {
      if (c.scene != scene) continue;
      columns.push_back(&c);
      for (const auto& [name, t] : c.passes)
        if (std::find(rows.begin(), rows.end(), name) == rows.end()) rows.push_back(name);
    }
    out << "\n### " << scene << " (" << columns.front()->triangles
        << " triangles): median ms per pass (x the floor pass of the same size)\n\n| pass |";
    for (const PassesCase* c : columns) out << ' ' << c->method << ' ' << sizeName(c->size) << " |";
    out << "\n|---|";
    for (size_t i = 0; i < columns.size(); ++i) out << "---:|";
    out << '\n';
    out << "| floor (1 read, 1 write per pixel) |";
    for (const PassesCase* c : columns) out << ' ' << fixed(c->floor.median, 2) << " |";
    out << '\n';
    for (const std::string& row : rows) {
      out << "| " << row << " |";
      for (const PassesCase* c : columns) {
        const auto it = std::find_if(c->passes.begin(), c->passes.end(), [&](const auto& p) { return p.first == row; });
        out << ' '
            << (it == c->passes.end() ? std::string()
                                      : fixed(it->second.median, 2) + " (" + fixed(it->second.median / c->floor.median, 1) + "x)")
            << " |";
      }
      out << '\n';
    }
    for (const PassesCase* c : columns)
      for (const auto& [name, reason] : c->skipped)
        out << "\n- " << c->method << ' ' << sizeName(c->size) << ": " << name << " skipped (" << reason << ')';
    out << '\n';
  }
}

}  // namespace hmb::bench
