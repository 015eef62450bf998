#include "bench/bvh_suite.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <random>
#include <thread>

#include "bench/bench_scenes.h"
#include "bench/embree_reference.h"
#include "bench/ray_query_anchor.h"
#include "bvh/reference_builder.h"
#include "bvh/reference_traversal.h"
#include "hmblur/aabb.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/report.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/bvh_build_pass.h"
#include "runtime/passes/linear_bvh_pass.h"
#include "runtime/passes/trace_rays_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::bench {
namespace {

// World-space triangles of a scene at its frame time, as one mesh.
struct Flat {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  bvh::TriangleList view() const { return {positions, indices, {}}; }
};

Flat flatten(const scene::Scene& scene) {
  Flat flat;
  for (const scene::Instance& instance : scene.instances) {
    const scene::Mesh& mesh = scene.meshes[instance.mesh];
    const glm::mat4 world = scene.worldMatrixAt(instance.node, scene.settings.frameTime);
    const auto base = static_cast<uint32_t>(flat.positions.size());
    for (const glm::vec3& p : mesh.positions) flat.positions.emplace_back(world * glm::vec4(p, 1.0f));
    for (uint32_t i : mesh.indices) flat.indices.push_back(base + i);
  }
  return flat;
}

std::vector<bvh::Ray> cameraRays(const scene::Scene& scene, ImageSize size) {
  const FrameCamera camera = frameCamera(scene, scene.settings.frameTime, size.width, size.height);
  const glm::mat4 clipToWorld = glm::inverse(camera.viewProjCurrent);
  std::vector<bvh::Ray> rays;
  for (uint32_t y = 0; y < size.height; ++y)
    for (uint32_t x = 0; x < size.width; ++x) {
      const glm::vec2 ndc(2.0f * (float(x) + 0.5f) / float(size.width) - 1.0f,
                          2.0f * (float(y) + 0.5f) / float(size.height) - 1.0f);
      // Depth is reversed: z/w = 1 at the near plane, 0.5 at twice its distance.
      const glm::vec4 near = clipToWorld * glm::vec4(ndc, 1.0f, 1.0f), far = clipToWorld * glm::vec4(ndc, 0.5f, 1.0f);
      const glm::vec3 a = glm::vec3(near) / near.w, b = glm::vec3(far) / far.w;
      rays.push_back(bvh::Ray{a, glm::normalize(b - a)});
    }
  return rays;
}

std::vector<bvh::Ray> randomRays(const Flat& flat, uint32_t count) {
  Aabb box;
  for (const glm::vec3& p : flat.positions) box.grow(p);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::normal_distribution<float> gauss;
  std::vector<bvh::Ray> rays;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 origin = box.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * box.extent();
    glm::vec3 d(gauss(rng), gauss(rng), gauss(rng));
    if (glm::length(d) == 0.0f) d = glm::vec3(0.0f, 0.0f, 1.0f);
    rays.push_back(bvh::Ray{origin, glm::normalize(d)});
  }
  return rays;
}

bool sameAnswer(const gpu::BvhHit& a, const gpu::BvhHit& b) {
  const bool aHit = a.triangle != HMB_NO_HIT, bHit = b.triangle != HMB_NO_HIT;
  return aHit == bHit && (!aHit || std::abs(a.t - b.t) <= 1e-4f * std::max(1.0f, std::abs(b.t)));
}

// Every ray on which the device and Embree disagree, judged by the exact answer.
Disagreements judgeDisagreements(const Flat& flat, std::span<const bvh::Ray> rays,
                                 std::span<const gpu::BvhHit> device, std::span<const gpu::BvhHit> embree) {
  Disagreements out;
  for (size_t i = 0; i < device.size(); ++i) {
    if (sameAnswer(device[i], embree[i])) continue;
    ++out.rays;
    const bvh::ExactHit exact = bvh::exactClosestHit(flat.view(), rays[i]);
    gpu::BvhHit truth{};
    truth.triangle = std::isfinite(exact.t) ? 0u : HMB_NO_HIT;
    truth.t = float(exact.t);
    const auto far = [](const gpu::BvhHit& h) { return h.triangle == HMB_NO_HIT ? INFINITY : double(h.t); };
    // A graze nearer than the farther answer can turn either test's answer.
    if (exact.grazeT <= std::max(far(device[i]), far(embree[i])) * (1.0 + 1e-4)) {
      ++out.grazes;
    } else if (!sameAnswer(device[i], truth)) {
      if (out.deviceWrong++ == 0) {
        char text[256];
        std::snprintf(text, sizeof(text), "ray %zu: device triangle %u at t %.9g, Embree %u at %.9g, exact t %.9g", i,
                      device[i].triangle, device[i].t, embree[i].triangle, embree[i].t, exact.t);
        out.firstDeviceWrong = text;
      }
    } else {
      ++out.embreeWrong;
    }
  }
  return out;
}

// Fails the run where a tracer is often wrong: a fast wrong tracer is no result.
void checkAgreement(const std::string& who, double agreement, const Disagreements& d) {
  if (agreement < kMinHitAgreement)
    throw Error(who + " and Embree hits agree on only " + std::to_string(agreement * 100.0) + "% of the rays");
  if (d.deviceWrong > 0)
    throw Error(who + "'s hit differs from the exact one on " + std::to_string(d.deviceWrong) +
                " rays that graze no edge (" + d.firstDeviceWrong + ")");
}

TraceFigures traceCase(const vk::Context& context, const TraceScene& traceScene, const passes::TraceRaysPass& pass,
                       const Flat& flat, std::span<const bvh::Ray> rays, const BvhSuiteOptions& options,
                       bool embree, RayQueryAnchor* anchor) {
  TraceFigures f;
  f.rays = static_cast<uint32_t>(rays.size());
  std::vector<gpu::TraceRay> traceRays;
  for (const bvh::Ray& r : rays)
    traceRays.push_back({glm::vec4(r.origin, r.tMin), glm::vec4(r.direction, r.tMax), 0u, HMB_IGNORE_NONE, 0u, 0u});
  const vk::Buffer rayBuffer = vk::uploadedBuffer(context, traceRays, "bench rays");
  const vk::Buffer hitBuffer(context, traceRays.size() * sizeof(gpu::BvhHit), vk::MemoryUse::Device, "bench hits");
  vk::FrameRecorder frame(context);
  std::vector<double> device;
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    frame.begin();
    pass.record(frame, traceScene, rayBuffer, hitBuffer, f.rays);
    const vk::FrameTimings timings = frame.submitAndWait();
    if (i >= options.warmup) device.push_back(timings.passes.at(0).milliseconds.value_or(NAN));
  }
  f.deviceMilliseconds = summarize(device);
  f.deviceMraysPerSecond = f.rays / (f.deviceMilliseconds.median * 1e3);
  const std::vector<gpu::BvhHit> hits = hitBuffer.download<gpu::BvhHit>();
  const std::span<const gpu::BvhHit> deviceHits = std::span(hits).first(rays.size());
  std::vector<gpu::BvhHit> embreeHits;
  if (embree) {
    EmbreeRun run = runEmbree(flat.view(), rays, embreeThreadCount(options.embreeThreads), options.warmup,
                              options.repeats);
    std::vector<double> ms;
    for (double s : run.traceSeconds) ms.push_back(s * 1e3);
    f.embreeMilliseconds = summarize(ms);
    f.embreeMraysPerSecond = f.rays / (f.embreeMilliseconds.median * 1e3);
    f.disagreements = judgeDisagreements(flat, rays, deviceHits, run.hits);
    f.hitAgreement = rays.empty() ? 1.0 : 1.0 - double(f.disagreements.rays) / double(rays.size());
    checkAgreement("device", f.hitAgreement, f.disagreements);
    embreeHits = std::move(run.hits);
  }
  if (anchor) {
    std::vector<double> ms;
    std::vector<gpu::BvhHit> anchorHits;
    for (int i = 0; i < options.warmup + options.repeats; ++i) {
      const double t = anchor->trace(rays, anchorHits);
      if (i >= options.warmup) ms.push_back(t);
    }
    f.anchorMilliseconds = summarize(ms);
    f.anchorMraysPerSecond = f.rays / (f.anchorMilliseconds.median * 1e3);
    // Judged against Embree where there is Embree, else against the device.
    f.anchorDisagreements =
        judgeDisagreements(flat, rays, anchorHits, embree ? std::span<const gpu::BvhHit>(embreeHits) : deviceHits);
    f.anchorAgreement = rays.empty() ? 1.0 : 1.0 - double(f.anchorDisagreements.rays) / double(rays.size());
    checkAgreement("the driver's ray query", f.anchorAgreement, f.anchorDisagreements);
  }
  return f;
}

// `traced` names the side judged (the first of the two compared).
nlohmann::json disagreementsJson(const Disagreements& d, const std::string& traced) {
  return {{"rays", d.rays},
          {"grazing_an_edge", d.grazes},
          {traced + "_wrong", d.deviceWrong},
          {"embree_wrong", d.embreeWrong}};
}

nlohmann::json traceJson(const TraceFigures& f) {
  nlohmann::json j = {{"rays", f.rays},
                      {"device_ms", summaryJson(f.deviceMilliseconds)},
                      {"embree_ms", summaryJson(f.embreeMilliseconds)},
                      {"device_mrays_per_s", f.deviceMraysPerSecond},
                      {"embree_mrays_per_s", f.embreeMraysPerSecond},
                      {"device_over_embree", f.deviceMraysPerSecond / f.embreeMraysPerSecond},
                      {"hit_agreement", f.hitAgreement},
                      {"disagreements", disagreementsJson(f.disagreements, "device")}};
  if (f.anchorMraysPerSecond > 0) {
    j["ray_query_ms"] = summaryJson(f.anchorMilliseconds);
    j["ray_query_mrays_per_s"] = f.anchorMraysPerSecond;
    j["device_over_ray_query"] = f.deviceMraysPerSecond / f.anchorMraysPerSecond;
    j["ray_query_hit_agreement"] = f.anchorAgreement;
    j["ray_query_disagreements"] = disagreementsJson(f.anchorDisagreements, "ray_query");
  }
  return j;
}

}  // namespace

int embreeThreadCount(int requested) {
  if (requested > 0) return requested;
  if (const char* lp = std::getenv("LP_NUM_THREADS"); lp && std::atoi(lp) > 0) return std::atoi(lp);
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

std::string rayQueryAnchorSkipped(const vk::Context& context, const BvhSuiteOptions& options) {
  if (!options.rayQueryAnchor) return "not asked for";
  return RayQueryAnchor::unavailableReason(context);
}

namespace {
// The world box of each instance's mesh at time t (its bounds through the instance's matrix):
// the top-level tree's primitives, as instance_motion_bounds makes them for one time.
std::vector<Aabb> instanceBoxesAt(const scene::Scene& scene, float t) {
  std::vector<Aabb> meshBounds(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (const glm::vec3& p : scene.meshes[m].positions) meshBounds[m].grow(p);
  std::vector<Aabb> boxes;
  for (const scene::Instance& instance : scene.instances)
    boxes.push_back(transformed(meshBounds.at(instance.mesh), scene.worldMatrixAt(instance.node, t)));
  return boxes;
}

// Where the build whose time is the summary's median lies among the builds (its stage times
// are reported with it); the first when the median falls between two builds.
size_t medianBuild(const std::vector<double>& builds, const Summary& summary) {
  const auto at = std::find(builds.begin(), builds.end(), summary.median);
  return at == builds.end() ? 0 : static_cast<size_t>(at - builds.begin());
}

void measureTopLevel(const vk::Context& context, const scene::Scene& source, const BvhSuiteOptions& options,
                     BvhCase& c) {
  c.instances = static_cast<uint32_t>(source.instances.size());
  if (c.instances < 2) return;
  const vk::Buffer boxes = vk::uploadedBuffer(
      context, passes::bvhBoxes(instanceBoxesAt(source, source.settings.frameTime)), "bench instance boxes");
  passes::BvhBuildPass tree(context, "bench top level", HMB_BVH_MAX_INSTANCE_LEAF,
                            passes::BvhBuildShape::forTopLevel(context));
  const glm::uvec2 root(0u, c.instances);
  std::vector<double> builds, smallTaskMs;
  std::vector<std::vector<double>> levels;
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    vk::FrameRecorder frame(context);
    const vk::FrameRecorder::ShapeMark buildStart = frame.mark();
    const passes::BvhBuildStats& stats = tree.build(frame, boxes, c.instances, std::span(&root, 1));
    c.topLevelFrame = frame.shapeSince(buildStart, vk::FrameRecorder::HostWaitsUntil::Now);
    if (i < options.warmup) continue;
    builds.push_back(stats.deviceMilliseconds);
    levels.push_back(stats.levelMilliseconds);
    smallTaskMs.push_back(stats.smallTaskMilliseconds);
    c.topLevelSmallTasks = stats.smallTasks;
  }
  c.topLevelMilliseconds = summarize(builds);
  const size_t at = medianBuild(builds, c.topLevelMilliseconds);
  c.topLevelLevelMilliseconds = levels.at(at);
  c.topLevelSmallTaskMilliseconds = smallTaskMs.at(at);

  passes::LinearBvhPass linear(context, "bench linear top level");
  std::vector<double> linearBuilds;
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    vk::FrameRecorder frame(context);
    const vk::FrameRecorder::ShapeMark buildStart = frame.mark();
    frame.begin();
    linear.record(frame, "bench linear top level", boxes, c.instances);
    const std::optional<double> ms = frame.submitAndWait().frameMilliseconds;
    c.topLevelLinearFrame = frame.shapeSince(buildStart);
    if (i >= options.warmup) linearBuilds.push_back(ms.value_or(0.0));
  }
  c.topLevelLinearMilliseconds = summarize(linearBuilds);
  c.topLevelLinearSahOverBinned = bvh::sahCost(linear.download()) / bvh::sahCost(tree.download(0));

  if (!TraceScene::whyNotSplit(source, TraceScene::kStillInstancesToSplit).empty()) return;
  const auto [order, still] = TraceScene::stillFirstOrder(source);
  passes::BvhBuildPass kept(context, "bench kept top level", HMB_BVH_MAX_INSTANCE_LEAF,
                            passes::BvhBuildShape::forTopLevel(context));
  vk::FrameRecorder frame(context);
  frame.begin();
  kept.recordKeptWithInsertions(frame, "bench kept top level", boxes, order, still);
  frame.submitAndWait();
  std::vector<double> insertions;
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    frame.begin();
    kept.recordInsertionsAgain(frame, "bench insertions", boxes);
    const std::optional<double> ms = frame.submitAndWait().frameMilliseconds;
    if (i >= options.warmup) insertions.push_back(ms.value_or(0.0));
  }
  c.topLevelInserted = c.instances - still;
  c.topLevelInsertionMilliseconds = summarize(insertions);
}
void measureTreelets(const vk::Context& context, const scene::Scene& scene, const Flat& flat,
                     const bvh::PrimitiveBounds& input, std::span<const bvh::Ray> coherent,
                     std::span<const bvh::Ray> incoherent, const passes::TraceRaysPass& tracePass,
                     const BvhSuiteOptions& options, bool embree, BvhCase& c) {
  passes::BvhBuildShape shape = passes::BvhBuildShape::forDevice(context);
  shape.treelets = true;
  std::vector<double> builds;
  std::vector<std::vector<std::pair<std::string, double>>> stages;
  std::unique_ptr<TraceScene> traceScene;
  for (int i = 0; i < options.warmup + options.repeats; ++i) {
    vk::FrameRecorder frame(context);
    traceScene.reset();
    traceScene = std::make_unique<TraceScene>(context, scene, frame, shape);
    if (i < options.warmup) continue;
    builds.push_back(traceScene->meshBvh().stats().deviceMilliseconds);
    stages.push_back(traceScene->meshBvh().stats().stageMilliseconds);
  }
  c.treeletBuildMilliseconds = summarize(builds);
  c.treeletStageMilliseconds = stages.at(medianBuild(builds, c.treeletBuildMilliseconds));
  c.treeletLevels = traceScene->meshBvh().stats().levels;
  c.sahTreelet = bvh::sahCost(traceScene->meshBvh().download(0));
  {
    const vk::Buffer boxes = vk::uploadedBuffer(context, passes::bvhBoxes(input.bounds), "bench boxes");
    passes::BvhBuildPass tree(context, "bench treelets", HMB_BVH_MAX_LEAF, shape);
    vk::FrameRecorder frame(context);
    const glm::uvec2 root(0u, c.triangles);
    const vk::FrameRecorder::ShapeMark start = frame.mark();
    tree.build(frame, boxes, c.triangles, std::span(&root, 1));
    c.treeletBuildFrame = frame.shapeSince(start, vk::FrameRecorder::HostWaitsUntil::Now);
  }
  vk::FrameRecorder frame(context);
  const float time = scene.settings.frameTime;
  traceScene->setShutterTimes(scene, std::span(&time, 1), frame);
  c.treeletCoherent = traceCase(context, *traceScene, tracePass, flat, coherent, options, embree, nullptr);
  c.treeletIncoherent = traceCase(context, *traceScene, tracePass, flat, incoherent, options, embree, nullptr);
}
}  // namespace

std::vector<BvhCase> runBvhSuite(const vk::Context& context, const BvhSuiteOptions& options, const Progress& progress) {
  if (!context.info().timestamps) throw Error("device " + context.info().name + " has no timestamps");
  const bool embree = embreeAvailable();
  if (!embree) progress("built without Embree: its columns stay empty");
  std::unique_ptr<RayQueryAnchor> anchor;
  if (const std::string skipped = rayQueryAnchorSkipped(context, options); skipped.empty())
    anchor = std::make_unique<RayQueryAnchor>(context);
  else
    progress("the driver's ray queries left out: " + skipped);
  std::vector<BvhCase> cases;
  const passes::TraceRaysPass tracePass(context);
  for (const std::string& name : options.scenes) {
    progress("scene " + name);
    const scene::Scene source = loadBenchScene(name);
    const Flat flat = flatten(source);
    const scene::Scene scene = scene::singleMeshScene(flat.positions, flat.indices);
    BvhCase c;
    c.scene = name;
    c.triangles = static_cast<uint32_t>(flat.indices.size() / 3);

    progress("  device builds");
    std::vector<double> builds;
    std::vector<std::vector<double>> levels;
    std::vector<double> smallTaskMs;
    std::vector<double> setups;
    std::unique_ptr<TraceScene> traceScene;
    for (int i = 0; i < options.warmup + options.repeats; ++i) {
      vk::FrameRecorder frame(context);
      traceScene.reset();
      // The whole setup a renderer waits for: uploads, the build, its compaction and the
      // triangles put in the leaves' order.
      const auto start = std::chrono::steady_clock::now();
      traceScene = std::make_unique<TraceScene>(context, scene, frame);
      const auto end = std::chrono::steady_clock::now();
      if (i < options.warmup) continue;
      setups.push_back(std::chrono::duration<double, std::milli>(end - start).count());
      builds.push_back(traceScene->meshBvh().stats().deviceMilliseconds);
      levels.push_back(traceScene->meshBvh().stats().levelMilliseconds);
      smallTaskMs.push_back(traceScene->meshBvh().stats().smallTaskMilliseconds);
    }
    c.deviceBuildMilliseconds = summarize(builds);
    c.setupWallMilliseconds = summarize(setups);
    const size_t median = medianBuild(builds, c.deviceBuildMilliseconds);
    c.deviceLevelMilliseconds = levels.at(median);
    c.deviceSmallTaskMilliseconds = smallTaskMs.at(median);
    c.deviceSmallTasks = traceScene->meshBvh().stats().smallTasks;
    c.deviceLevels = traceScene->meshBvh().stats().levels;
    c.deviceBuildShape = traceScene->meshBvh().shape().describe();
    c.sahDevice = bvh::sahCost(traceScene->meshBvh().download(0));

    progress("  CPU full-sweep build");
    const bvh::PrimitiveBounds input = bvh::triangleBounds(flat.view());
    {
      // Refit of the same tree to the same boxes: what a deforming mesh pays per frame instead
      // of a build (the work does not depend on how far the triangles moved).
      const vk::Buffer boxBuffer = vk::uploadedBuffer(context, passes::bvhBoxes(input.bounds), "bench boxes");
      passes::BvhBuildPass tree(context, "bench refit", HMB_BVH_MAX_LEAF);
      vk::FrameRecorder frame(context);
      const glm::uvec2 root(0u, c.triangles);
      const vk::FrameRecorder::ShapeMark buildStart = frame.mark();
      tree.build(frame, boxBuffer, c.triangles, std::span(&root, 1));
      c.deviceBuildFrame = frame.shapeSince(buildStart, vk::FrameRecorder::HostWaitsUntil::Now);
      std::vector<double> refits;
      // The first refit also prepares the next ones (parents, depths, the nodes by depth).
      c.deviceFirstRefitMilliseconds = tree.refit(frame, boxBuffer);
      for (int i = 0; i < options.warmup + options.repeats; ++i) {
        const double ms = tree.refit(frame, boxBuffer);
        if (i >= options.warmup) refits.push_back(ms);
      }
      c.deviceRefitMilliseconds = summarize(refits);
    }
    const auto start = std::chrono::steady_clock::now();
    const bvh::Bvh reference = bvh::buildReferenceSah(input.bounds, input.centroids);
    c.cpuReferenceBuildMilliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    c.sahReference = bvh::sahCost(reference);

    vk::FrameRecorder frame(context);
    const float time = scene.settings.frameTime;
    traceScene->setShutterTimes(scene, std::span(&time, 1), frame);
    const std::vector<bvh::Ray> coherent = cameraRays(source, options.coherentSize);
    const std::vector<bvh::Ray> incoherent = randomRays(flat, options.incoherentRays);
    if (embree) {
      progress("  Embree builds");
      const EmbreeRun run = runEmbree(flat.view(), {}, embreeThreadCount(options.embreeThreads), options.warmup,
                                      options.repeats);
      std::vector<double> sceneMs, bvhMs;
      for (double s : run.sceneBuildSeconds) sceneMs.push_back(s * 1e3);
      for (double s : run.bvhBuildSeconds) bvhMs.push_back(s * 1e3);
      c.embreeSceneBuildMilliseconds = summarize(sceneMs);
      c.embreeBvhBuildMilliseconds = summarize(bvhMs);
      c.sahEmbree = bvh::sahCost(run.bvh);
    }
    if (anchor) {
      progress("  the driver's acceleration-structure builds");
      std::vector<double> ms;
      for (int i = 0; i < options.warmup + options.repeats; ++i) {
        const double t = anchor->build(flat.view());
        if (i >= options.warmup) ms.push_back(t);
      }
      c.anchorBuildMilliseconds = summarize(ms);
      c.anchorMeasured = true;
    }
    progress("  top-level tree");
    measureTopLevel(context, source, options, c);
    progress("  coherent rays");
    c.coherent = traceCase(context, *traceScene, tracePass, flat, coherent, options, embree, anchor.get());
    progress("  incoherent rays");
    c.incoherent = traceCase(context, *traceScene, tracePass, flat, incoherent, options, embree, anchor.get());
    traceScene.reset();
    progress("  treelet builds, and rays through their trees");
    measureTreelets(context, scene, flat, input, coherent, incoherent, tracePass, options, embree, c);
    cases.push_back(std::move(c));
  }
  return cases;
}

namespace {
nlohmann::json stageJson(const std::vector<std::pair<std::string, double>>& stages) {
  nlohmann::json json = nlohmann::json::object();
  for (const auto& [stage, ms] : stages) json[stage] = ms;
  return json;
}

// "optimize 61%": the stage that took most of a build, and its share.
std::string slowestStage(const std::vector<std::pair<std::string, double>>& stages) {
  if (stages.empty()) return "-";
  double total = 0.0;
  const std::pair<std::string, double>* slowest = &stages.front();
  for (const auto& stage : stages) {
    total += stage.second;
    if (stage.second > slowest->second) slowest = &stage;
  }
  return slowest->first + " " + std::to_string(int(std::lround(100.0 * slowest->second / std::max(total, 1e-9)))) + "%";
}
}  // namespace

nlohmann::json bvhCaseJson(const BvhCase& c) {
  const double mtris = c.triangles / (c.deviceBuildMilliseconds.median * 1e3);
  const double embreeMtris = c.triangles / (c.embreeSceneBuildMilliseconds.median * 1e3);
  return {{"scene", c.scene},
          {"triangles", c.triangles},
          {"build",
           {{"device_ms", summaryJson(c.deviceBuildMilliseconds)},
            {"device_mtris_per_s", mtris},
            {"device_levels", c.deviceLevels},
            {"device_build_shape", c.deviceBuildShape},
            {"device_frame", frameShapeJson(c.deviceBuildFrame)},
            {"device_level_ms", c.deviceLevelMilliseconds},
            {"device_small_tasks", c.deviceSmallTasks},
            {"device_small_task_ms", c.deviceSmallTaskMilliseconds},
            {"device_refit_ms", summaryJson(c.deviceRefitMilliseconds)},
            {"device_first_refit_ms", c.deviceFirstRefitMilliseconds},
            {"setup_wall_ms", summaryJson(c.setupWallMilliseconds)},
            {"embree_scene_ms", summaryJson(c.embreeSceneBuildMilliseconds)},
            {"embree_mtris_per_s", embreeMtris},
            {"embree_build_bvh_ms", summaryJson(c.embreeBvhBuildMilliseconds)},
            {"device_over_embree_speed", mtris / embreeMtris},
            {"cpu_full_sweep_ms", c.cpuReferenceBuildMilliseconds},
            {"ray_query_build_ms", c.anchorMeasured ? summaryJson(c.anchorBuildMilliseconds) : nlohmann::json()},
            {"device_over_ray_query_build_speed",
             c.anchorMeasured ? nlohmann::json(c.anchorBuildMilliseconds.median / c.deviceBuildMilliseconds.median)
                              : nlohmann::json()}}},
          {"sah",
           {{"device", c.sahDevice},
            {"cpu_full_sweep", c.sahReference},
            {"embree_build_bvh", c.sahEmbree},
            {"device_over_full_sweep", c.sahDevice / c.sahReference},
            {"embree_over_full_sweep", c.sahEmbree / c.sahReference}}},
          {"coherent", traceJson(c.coherent)},
          {"incoherent", traceJson(c.incoherent)},
          {"treelet_build",
           {{"device_ms", summaryJson(c.treeletBuildMilliseconds)},
            {"device_mtris_per_s", c.triangles / (c.treeletBuildMilliseconds.median * 1e3)},
            {"over_profile_builder_time", c.treeletBuildMilliseconds.median / c.deviceBuildMilliseconds.median},
            {"stage_ms", stageJson(c.treeletStageMilliseconds)},
            {"device_frame", frameShapeJson(c.treeletBuildFrame)},
            {"device_levels", c.treeletLevels},
            {"sah", c.sahTreelet},
            {"sah_over_full_sweep", c.sahTreelet / c.sahReference},
            {"coherent", traceJson(c.treeletCoherent)},
            {"incoherent", traceJson(c.treeletIncoherent)}}},
          {"top_level",
           c.instances < 2 ? nlohmann::json()
                           : nlohmann::json{{"instances", c.instances},
                                            {"device_ms", summaryJson(c.topLevelMilliseconds)},
                                            {"device_level_ms", c.topLevelLevelMilliseconds},
                                            {"device_small_tasks", c.topLevelSmallTasks},
                                            {"device_small_task_ms", c.topLevelSmallTaskMilliseconds},
                                            {"device_frame", frameShapeJson(c.topLevelFrame)},
                                            {"linear_ms", summaryJson(c.topLevelLinearMilliseconds)},
                                            {"linear_frame", frameShapeJson(c.topLevelLinearFrame)},
                                            {"linear_sah_over_binned", c.topLevelLinearSahOverBinned},
                                            {"inserted", c.topLevelInserted},
                                            {"insertion_ms", c.topLevelInserted == 0
                                                                 ? nlohmann::json()
                                                                 : summaryJson(c.topLevelInsertionMilliseconds)}}}};
}

void printBvhTable(std::ostream& out, const std::vector<BvhCase>& cases) {
  out << std::fixed;
  out << "| scene | triangles | device build ms (Mtris/s) | Embree build ms (Mtris/s) | build speed ratio | SAH device / "
         "full sweep (Embree) | coherent Mrays/s device / Embree (ratio) | incoherent Mrays/s device / Embree (ratio) |\n"
      << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const BvhCase& c : cases) {
    const double mtris = c.triangles / (c.deviceBuildMilliseconds.median * 1e3);
    const double embreeMtris = c.triangles / (c.embreeSceneBuildMilliseconds.median * 1e3);
    out << "| " << c.scene << " | " << c.triangles << " | " << std::setprecision(1) << c.deviceBuildMilliseconds.median
        << " (" << std::setprecision(3) << mtris << ") | " << std::setprecision(1)
        << c.embreeSceneBuildMilliseconds.median << " (" << std::setprecision(2) << embreeMtris << ") | "
        << std::setprecision(3) << mtris / embreeMtris << "x | " << c.sahDevice / c.sahReference << "x ("
        << c.sahEmbree / c.sahReference << "x) | ";
    for (const TraceFigures* f : {&c.coherent, &c.incoherent})
      out << std::setprecision(2) << f->deviceMraysPerSecond << " / " << f->embreeMraysPerSecond << " ("
          << std::setprecision(3) << f->deviceMraysPerSecond / f->embreeMraysPerSecond << "x) | ";
    out << "\n";
  }
  out << "\nThe treelet builder (the GPU profile's mesh builder) on the same triangles and rays:\n\n"
      << "| scene | triangles | build ms (Mtris/s) | over the profile's build | slowest stage | dispatches | host waits | "
         "levels | SAH / full sweep | coherent Mrays/s (agreement) | incoherent Mrays/s (agreement) |\n"
      << "|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|\n";
  for (const BvhCase& c : cases) {
    out << "| " << c.scene << " | " << c.triangles << " | " << std::setprecision(1) << c.treeletBuildMilliseconds.median
        << " (" << std::setprecision(3) << c.triangles / (c.treeletBuildMilliseconds.median * 1e3) << ") | "
        << std::setprecision(2) << c.treeletBuildMilliseconds.median / c.deviceBuildMilliseconds.median << "x | "
        << slowestStage(c.treeletStageMilliseconds) << " | " << c.treeletBuildFrame.dispatches << " | " << c.treeletBuildFrame.hostWaits << " | " << c.treeletLevels << " | "
        << std::setprecision(3) << c.sahTreelet / c.sahReference << "x | ";
    for (const TraceFigures* f : {&c.treeletCoherent, &c.treeletIncoherent})
      out << std::setprecision(2) << f->deviceMraysPerSecond << " (" << std::setprecision(2) << 100.0 * f->hitAgreement
          << "%) | ";
    out << "\n";
  }
  if (std::any_of(cases.begin(), cases.end(), [](const BvhCase& c) { return c.instances >= 2; })) {
    out << "\nThe top-level tree over each scene's instances (the same builder, a frame's top level):\n\n"
        << "| scene | instances | device build ms | levels (their ms) | small tasks (their ms) | the rest ms (begin, "
           "dispatch sizing, gaps) | moving ones inserted into the still ones' kept tree ms | dispatches | linear "
           "builder ms (dispatches) | linear SAH / binned |\n"
        << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const BvhCase& c : cases) {
      if (c.instances < 2) continue;
      double levelMs = 0.0;
      for (const double ms : c.topLevelLevelMilliseconds) levelMs += ms;
      out << "| " << c.scene << " | " << c.instances << " | " << std::setprecision(2) << c.topLevelMilliseconds.median
          << " | " << c.topLevelLevelMilliseconds.size() << " (" << levelMs << ") | " << c.topLevelSmallTasks << " ("
          << c.topLevelSmallTaskMilliseconds << ") | "
          << c.topLevelMilliseconds.median - levelMs - c.topLevelSmallTaskMilliseconds << " | ";
      if (c.topLevelInserted == 0)
        out << "not split | ";
      else
        out << c.topLevelInserted << " (" << c.topLevelInsertionMilliseconds.median << ") | ";
      out << c.topLevelFrame.dispatches << " | " << c.topLevelLinearMilliseconds.median << " ("
          << c.topLevelLinearFrame.dispatches << ") | " << std::setprecision(3) << c.topLevelLinearSahOverBinned << " |\n";
    }
  }
  if (std::none_of(cases.begin(), cases.end(), [](const BvhCase& c) { return c.anchorMeasured; })) return;
  out << "\nThe driver's own acceleration structures and ray queries, same triangles and rays:\n\n"
      << "| scene | its build ms (ours over it, speed) | coherent Mrays/s (ours over it) | incoherent Mrays/s "
         "(ours over it) |\n"
      << "|---|---:|---:|---:|\n";
  for (const BvhCase& c : cases) {
    if (!c.anchorMeasured) continue;
    out << "| " << c.scene << " | " << std::setprecision(1) << c.anchorBuildMilliseconds.median << " ("
        << std::setprecision(3) << c.anchorBuildMilliseconds.median / c.deviceBuildMilliseconds.median << "x) | ";
    for (const TraceFigures* f : {&c.coherent, &c.incoherent})
      out << std::setprecision(2) << f->anchorMraysPerSecond << " (" << std::setprecision(2)
          << f->deviceMraysPerSecond / f->anchorMraysPerSecond << "x) | ";
    out << "\n";
  }
}

}  // namespace hmb::bench
