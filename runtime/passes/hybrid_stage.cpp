#include "runtime/passes/hybrid_stage.h"

#include <algorithm>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/post_process_stage.h"

namespace hmb::passes {

namespace {

// Whether `plan` (the stage's own for the frame) takes the shared mesh trees: it skipped their
// build as shared, so prepare() need not fingerprint the scene's meshes a second time.
bool planSharesMeshTrees(const FramePlan& plan) {
  for (const PlannedPass& pass : plan.passes())
    if (pass.name == HybridStage::kBvhMeshes) return !pass.run && pass.reason == kSharedMeshTreesReason;
  return false;
}

// Why a frame traces no shutter rays; empty when it does.
std::string shutterRaysSkipped(const scene::Scene& scene, const HybridSettings& settings) {
  if (settings.shutterRays == 0) return kShutterRaysOffReason;
  if (scene.hasDeformation())
    return "deforming meshes are traced at the frame time only: shutter rays would see them in the wrong pose";
  return {};
}

// The trace scene's times: the frame's first (the reveal's), then each shutter stratum's centre.
std::vector<float> traceTimes(const scene::Scene& scene, float frameTime, const HybridSettings& settings) {
  std::vector<float> times = {frameTime};
  if (!shutterRaysSkipped(scene, settings).empty()) return times;
  const float exposure = settings.blur.exposure;
  for (uint32_t s = 0; s < settings.shutterRays; ++s)
    times.push_back(frameTime - exposure + exposure * (float(s) + 0.5f) / float(settings.shutterRays));
  return times;
}

// Why a frame leaves the paper's reveal out: with every listed pixel's shutter rays it re-renders
// nearly every pixel the reveal would, and the image hardly moved against the reference where it
// ran (docs/hybrid.md, "The hybrid method"). Under a ray budget the pixels left untraced keep
// the reveal's composite.
std::string revealSkipped(const scene::Scene& scene, const HybridSettings& settings) {
  return shutterRaysSkipped(scene, settings).empty() && settings.rayBudget == 0 ? kRevealLeftToShutterRaysReason
                                                                                 : "";
}

}  // namespace

HybridStage::HybridStage(const vk::Context& context, PostProcessStage& postProcess, const HitShading* hits)
    : context_(context),
      passes_(context),
      postProcess_(postProcess),
      rayMask_(context),
      reveal_(context, hits),
      gather_(context),
      backgroundGather_(context),
      composite_(context),
      shutterRays_(context, hits) {
  const auto withoutShutterRays = [](const Frame& f) { return shutterRaysSkipped(*f.scene, *f.settings); };
  const auto withoutBudget = [](const Frame& f) {
    const std::string skipped = shutterRaysSkipped(*f.scene, *f.settings);
    if (!skipped.empty()) return skipped;
    return f.settings->rayBudget == 0 ? std::string(kNoRayBudgetReason) : std::string();
  };
  const auto withoutReveal = [](const Frame& f) { return revealSkipped(*f.scene, *f.settings); };
  passes_
      // The trace scene's trees: the meshes' (scene setup) and the still instances' are built
      // by prepare(), which reads the plan; the deforming meshes' refit (over the vertices the
      // frame's deformation wrote) and the instances' tree at the frame's times are built in
      // the frame.
      .group([this](FramePlan& plan, const Frame& f) { planTrees(plan, *f.scene, f.frameTime, *f.settings); },
             [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
               if (plan.runs(TraceScene::kRefit)) traceScene_->recordRefit(*f.gpuScene, frame);
               if (plan.runs(kBvhInstances)) traceScene_->recordStagedShutterTimes(frame, kBvhInstances);
             })
      // The gather's tiles; the whole mask's tile-max also lists its edge candidates.
      .group([this](FramePlan& plan, const Frame&) { postProcess_.planTiles(plan); },
             [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
               if (!plan.runs(TileMaxPass::kName)) return;
               if (f.mask.movingTilesOnly) {
                 postProcess_.recordTiles(frame, f.raster);
               } else {
                 rayMask_.recordTileMax(frame, f.raster, f.mask);
                 postProcess_.recordNeighborMax(frame);
               }
             })
      .group(
          [this](FramePlan& plan, const Frame& f) {
            rayMask_.plan(plan, revealSkipped(*f.scene, *f.settings),
                          f.settings->composite == HybridComposite::Coverage
                              ? ""
                              : "composite weights: the composite takes its own samples, and every mask pixel is "
                                "revealed");
          },
          [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
            if (plan.runs(RayMaskStage::kClear)) rayMask_.record(frame, f.raster, f.mask);
          })
      .pass(
          kShutterRaysList,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            shutterRays_.recordList(frame, f.raster, f.blur, postProcess_.tileMax(), rayMask_, shutterStrata_);
          },
          withoutShutterRays)
      .pass(
          kShutterRaysBudget, [this](vk::FrameRecorder& frame, const Frame&) { shutterRays_.recordBudget(frame); },
          withoutBudget)
      // Post-process's image. Beside the reveal the composite writes the mask's pixels over it, so
      // the gather may leave them out where the device profile says that pays
      // (DeviceProfile::gatherSkipsRayMask).
      .group([this](FramePlan& plan, const Frame&) { gather_.plan(plan); },
             [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
               if (!plan.runs(GatherPass::kName)) return;
               if (plan.runs(RevealPass::kName) && context_.profile().gatherSkipsRayMask)
                 gather_.recordOutsideMask(frame, f.raster, postProcess_.neighborMax(), *f.output, settings_.blur,
                                           rayMask_.mask());
               else
                 gather_.record(frame, f.raster, postProcess_.neighborMax(), *f.output, settings_.blur);
             })
      .pass(
          RevealPass::kName,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            recordTraceStart(frame, RevealPass::kName);
            reveal_.record(frame, *traceScene_, *f.gpuScene, cameraRays_, *f.layer, rayMask_.list(),
                           rayMask_.counters(), revealed_, size_.width(), size_.height(), settings_);
          },
          withoutReveal)
      // The background layer: the revealed surfaces over the raster, gathered at the revealed
      // pixels only; with the coverage composite blended under the mask's foreground into the
      // image there, the composite taking the mask's other pixels.
      .pass(
          kGatherBackground,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            const bool coverage = settings_.composite == HybridComposite::Coverage;
            backgroundGather_.record(frame, *f.layer, revealed_, postProcess_.neighborMax(), rayMask_.mask(),
                                     rayMask_.list(), rayMask_.counters(), coverage ? *f.output : backgroundBlurred_,
                                     f.blur, f.raster.shutterPaths, coverage ? &rayMask_.coverage() : nullptr);
          },
          withoutReveal)
      // Beside the coverage composite there is no background buffer: the coverage stands in for
      // its unread binding.
      .pass(
          kComposite,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            const bool coverage = settings_.composite == HybridComposite::Coverage;
            composite_.record(frame, *f.layer, postProcess_.neighborMax(), rayMask_.list(), rayMask_.counters(),
                              coverage ? rayMask_.coverage() : backgroundBlurred_, *f.output, f.blur,
                              settings_.composite, f.raster.shutterPaths,
                              coverage ? &rayMask_.coverage() : nullptr);
          },
          withoutReveal)
      .pass(
          kShutterRaysTrace,
          [this](vk::FrameRecorder& frame, const Frame& f) {
            recordTraceStart(frame, kShutterRaysTrace);
            shutterRays_.recordTrace(frame, *traceScene_, *f.gpuScene, cameraRays_, shutterStrata_, *f.output);
          },
          withoutShutterRays);
}

HybridStage::~HybridStage() = default;

std::optional<HybridStage::TreeBytes> HybridStage::meshTreeBytes() const {
  if (!traceScene_ || traceScene_->triangleCount() == 0) return std::nullopt;
  const double triangles = traceScene_->triangleCount();
  const passes::BvhBuildPass& trees = traceScene_->meshBvh();
  return TreeBytes{double(trees.allocatedTreeBytes()) / triangles, double(trees.usedTreeBytes()) / triangles};
}

uint32_t HybridStage::cutTraces() const { return traceScene_ ? traceScene_->cutTraces() : 0u; }

void HybridStage::forgetTraceScene() { traceScene_.reset(); }

void HybridStage::shareMeshTrees(std::shared_ptr<SharedMeshTrees> shared) { sharedTrees_ = std::move(shared); }

bool HybridStage::takesSharedTrees(const scene::Scene& scene) const {
  return sharedTrees_ && sharedTrees_->trees && !scene.hasDeformation() && sharedTrees_->trees->serves(scene);
}

void HybridStage::plan(FramePlan& plan, const scene::Scene& scene, float frameTime,
                       const HybridSettings& settings) const {
  Frame f;
  f.scene = &scene;
  f.frameTime = frameTime;
  f.settings = &settings;
  passes_.plan(plan, f);
}

void HybridStage::planTrees(FramePlan& plan, const scene::Scene& scene, float frameTime,
                            const HybridSettings& settings) const {
  bool sameMeshes = false;
  if (takesSharedTrees(scene)) {
    plan.skip(kBvhMeshes, kSharedMeshTreesReason);
    sameMeshes = traceScene_ && traceScene_->meshTrees() == sharedTrees_->trees;
  } else {
    sameMeshes = planKeptMeshTrees(plan, kBvhMeshes, traceScene_.get(), scene);
  }
  planDeformedTrees(plan, scene);
  const std::vector<float> times = traceTimes(scene, frameTime, settings);
  if (sameMeshes && !scene.hasDeformation() && traceScene_->hasShutterTimes(scene, times))
    plan.skip(kBvhInstances, "the top-level tree of the last frame serves this one: no instance moved since");
  else
    plan.run(kBvhInstances);
  // Only a split top level has the still instances' tree (scene setup, as the mesh trees).
  if (TraceScene::whyNotSplit(scene, TraceScene::kStillInstancesToSplit).empty()) {
    if (sameMeshes && traceScene_->hasStillInstanceTreeOf(scene))
      plan.skip(kBvhStillInstances, "the still instances' tree of an earlier frame serves this one");
    else
      plan.run(kBvhStillInstances);
  }
}

HybridStage::PrepareTimings HybridStage::prepare(vk::FrameRecorder& frame, const scene::Scene& scene, float frameTime,
                                                 uint32_t width, uint32_t height, const HybridSettings& settings,
                                                 const FramePlan& plan) {
  validate(settings);
  if (postProcess_.settings() != settings.blur)
    throw Error("hybrid: the post-process stage must be configured with the hybrid's blur settings");
  settings_ = settings;
  PrepareTimings timings;
  // plan() decided what the last frame's trees still serve; only the others are built.
  const vk::FrameRecorder::ShapeMark meshesStart = frame.mark();
  if (planSharesMeshTrees(plan)) {
    if (!sharedTrees_ || !sharedTrees_->trees) throw Error("hybrid: the plan shares mesh trees this stage was not given");
    if (!traceScene_ || traceScene_->meshTrees() != sharedTrees_->trees) {
      traceScene_.reset();
      traceScene_ = std::make_unique<TraceScene>(context_, sharedTrees_->trees);
    }
  } else if (const std::optional<double> meshMs =
                 prepareKeptMeshTrees(traceScene_, kBvhMeshes, plan, context_, scene, frame)) {
    timings.setup = {{{kBvhMeshes, *meshMs}}, *meshMs};
  }
  if (sharedTrees_ && !scene.hasDeformation()) sharedTrees_->trees = traceScene_->meshTrees();
  timings.setupShape = frame.shapeSince(meshesStart, vk::FrameRecorder::HostWaitsUntil::Now);
  const std::vector<float> times = traceTimes(scene, frameTime, settings);
  shutterStrata_ = plan.runs(kShutterRaysTrace) ? settings.shutterRays : 0u;
  candidatesInTileMaxLoop_ = context_.profile().edgeCandidatesInTileMax || cameraMovesOnScreen(scene, frameTime);
  if (shutterStrata_ != 0 && times.size() != shutterStrata_ + 1)
    throw Error("hybrid: the plan traces shutter rays that these settings leave out");
  // The refit is recorded in the frame (record()); its host part, which waits only the first
  // time after a build, is setup.
  if (plan.runs(TraceScene::kRefit)) {
    const vk::FrameRecorder::ShapeMark refitStart = frame.mark();
    if (const double ms = traceScene_->prepareRefit(scene, frame); ms > 0.0)
      vk::appendTimings(timings.setup, {{{TraceScene::kRefit, ms}}, ms});
    timings.setupShape += frame.shapeSince(refitStart, vk::FrameRecorder::HostWaitsUntil::Now);
  }
  const bool buildsInstanceTree = plan.runs(kBvhInstances);
  traceScene_->splitTopLevel(TraceScene::kStillInstancesToSplit);
  if (buildsInstanceTree) traceScene_->stageShutterTimes(scene, times);
  if (buildsInstanceTree && plan.runs(kBvhStillInstances) && !traceScene_->keepsStillInstanceTree()) {
    const vk::FrameRecorder::ShapeMark stillStart = frame.mark();
    const double ms = traceScene_->buildStillInstanceTree(frame);
    vk::appendTimings(timings.setup, {{{kBvhStillInstances, ms}}, ms});
    timings.setupShape += frame.shapeSince(stillStart, vk::FrameRecorder::HostWaitsUntil::Now);
  }
  cameras_.clear();
  for (const float t : times) cameras_.push_back(pinholeCamera(scene, t, width, height));
  const uint64_t cameraBytes = cameras_.size() * sizeof(gpu::PinholeCamera);
  if (!cameraRays_.handle() || cameraRays_.size() < cameraBytes)
    cameraRays_ = vk::Buffer(context_, cameraBytes, vk::MemoryUse::Device, "camera rays (frame, shutter strata)");
  if (shutterStrata_ != 0) shutterRays_.prepare(width, height, settings.rayBudget);

  // Beside the shutter rays the mask's own buffers and the reveal's layers are not made (64
  // bytes a pixel): the frame lists the moving tiles alone.
  const bool reveals = plan.runs(RevealPass::kName);
  reveals_ = reveals;
  rayMask_.prepare(width, height, !reveals, settings.composite == HybridComposite::Coverage);
  const bool resized = size_.changesTo(width, height);
  size_.madeFor(width, height);
  // The weights composite reads the blurred background from a buffer of its own; the coverage
  // composite is blended where the background is gathered.
  const bool weights = settings.composite == HybridComposite::Weights;
  const uint64_t pixels = uint64_t(width) * height;
  if (!reveals) {
    revealed_ = {};
  } else if (resized || !revealed_.samples().handle()) {
    revealed_ = {};  // the old layer goes first: the two never take memory at once
    revealed_ = ImageLayer::allocate(context_, pixels, "revealed", ImageLayer::Velocities::None);
  }
  if (!reveals || !weights)
    backgroundBlurred_ = {};
  else if (resized || !backgroundBlurred_.handle())
    backgroundBlurred_ =
        vk::Buffer(context_, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "background blurred (mask pixels)");
  return timings;
}

void HybridStage::record(vk::FrameRecorder& frame, const FramePlan& plan, const ImageLayer& layer,
                         const GpuScene& gpuScene, const vk::Buffer& output, const vk::Buffer* shutterPaths) {
  if (!traceScene_) throw Error("hybrid: record() before prepare()");
  const bool curved = settings_.blur.motionPath == MotionPath::Curved;
  if (curved && !shutterPaths) throw Error("hybrid: the curved motion path needs the G-buffer's shutter paths");
  Frame f;
  f.layer = &layer;
  f.gpuScene = &gpuScene;
  f.output = &output;
  f.raster = {&layer.samples(), &layer.surfaces(), &layer.velocities(), size_.width(), size_.height(),
              curved ? shutterPaths : nullptr};
  // One set of gather parameters for the frame: the mask must find the pixels the two gathers
  // blur, as they blur them.
  f.blur = gatherParams(settings_.blur, size_.width(), size_.height(),
                        {settings_.maskBackgroundBoost, settings_.maskForegroundDivide});
  if (curved) f.blur.flags |= HMB_GATHER_FLAG_CURVED_PATH;
  f.mask.tileMax = &postProcess_.tileMax();
  f.mask.blur = f.blur;
  f.mask.edgeThreshold = settings_.edgeThreshold;
  // The coverage composite weights the revealed background by 1 - alpha: pixels whose samples
  // all stay on their object (alpha exactly 1) need no reveal.
  f.mask.listOnlyUncovered = settings_.composite == HybridComposite::Coverage;
  // Where the shutter rays stand in for the reveal (plan()), the mask's stage lists the moving
  // tiles their list walks, and post-process's image is theirs to correct.
  f.mask.movingTilesOnly = !reveals_;
  f.mask.candidatesInTileMaxLoop = candidatesInTileMaxLoop_;
  passes_.record(frame, plan, f);
}

void HybridStage::recordTraceStart(vk::FrameRecorder& frame, const char* pass) const {
  frame.write(pass, cameraRays_, std::span<const gpu::PinholeCamera>(cameras_));
  traceScene_->recordResetStatus(frame, pass);
}

}  // namespace hmb::passes
