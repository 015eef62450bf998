#include "runtime/passes/reference_stage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "hmblur/hit_shading.h"
#include "kernels/manifest.h"
#include "kernels/reference/reference_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/deformed_vertices.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "scenes/deformation.h"

namespace hmb::passes {
namespace {

// SplitMix64: the per-stratum jitter from the seed (host side, shared by all pixels).
uint64_t splitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A step coprime to n near n / golden ratio: k -> k * step mod n visits every stratum once,
// and any run of consecutive k is spread over the whole shutter.
uint32_t spreadingStep(uint32_t n) {
  if (n <= 2) return 1;
  uint32_t step = std::max(1u, static_cast<uint32_t>(std::lround(double(n) * 0.6180339887498949)));
  while (std::gcd(step, n) != 1) ++step;
  return step;
}

bool sameCamera(const gpu::PinholeCamera& a, const gpu::PinholeCamera& b) {
  return a.eye == b.eye && a.right == b.right && a.down == b.down && a.forward == b.forward;
}

// Whether the instance can show something else at another time: it is animated, or its
// deformation is.
bool instanceMoves(const scene::Scene& scene, const scene::Instance& instance) {
  return scene.isAnimated(instance.node) || (instance.deforms() && scene::deformationIsAnimated(scene, instance));
}

// World boxes of every moving instance, each the union of its mesh's box (deformed at each
// time, for a deforming one) carried to the world at every sample time: nothing it shows at
// those times lies outside.
std::vector<glm::vec4> sweptBoxesOfMovingInstances(const scene::Scene& scene, std::span<const float> times) {
  std::vector<glm::vec4> boxes;
  for (const scene::Instance& instance : scene.instances) {
    if (!instanceMoves(scene, instance)) continue;
    const scene::Mesh& mesh = scene.meshes.at(instance.mesh);
    if (mesh.positions.empty()) continue;
    Aabb rest;
    for (const glm::vec3& p : mesh.positions) rest.grow(p);
    glm::vec3 worldLo(std::numeric_limits<float>::max()), worldHi(-std::numeric_limits<float>::max());
    for (const float t : times) {
      const Aabb box = instance.deforms() ? scene::deformedBoundsAt(scene, instance, t) : rest;
      const glm::vec3 lo = box.min, hi = box.max;
      const glm::mat4 world = scene.worldMatrixAt(instance.node, t);
      for (int corner = 0; corner < 8; ++corner) {
        const glm::vec3 p((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
        const glm::vec3 w = glm::vec3(world * glm::vec4(p, 1.0f));
        worldLo = glm::min(worldLo, w);
        worldHi = glm::max(worldHi, w);
      }
    }
    // Widened by a relative margin for the rounding of the transforms and of the box test.
    const glm::vec3 margin = (glm::abs(worldLo) + glm::abs(worldHi) + (worldHi - worldLo)) * 1e-5f;
    boxes.emplace_back(worldLo - margin, 0.0f);
    boxes.emplace_back(worldHi + margin, 0.0f);
  }
  return boxes;
}


// What a checkpoint must match to be resumed, and parts to be merged: the scene, the image and
// every setting that changes which samples are taken or what they see.
nlohmann::json checkpointIdentity(const scene::Scene& scene, float frameTime, uint32_t width, uint32_t height,
                                  const ReferenceSettings& settings, const HitShading* hits) {
  std::string shading = "the library's";
  if (hits && hits->custom()) {
    uint64_t hash = 0xcbf29ce484222325ull;
    for (const std::string* text : {&hits->shadeHit(), &hits->shadeMiss()}) {
      for (const char c : *text) hash = (hash ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
      hash *= 0x100000001b3ull;  // the end of a text: "ab" + "" differs from "a" + "b"
    }
    shading = "a user's, text hash " + std::to_string(hash);
  }
  return {{"scene", scene.name},
          {"triangles", scene.triangleCount()},
          {"instances", scene.instances.size()},
          {"meshes_fingerprint", meshFingerprint(scene)},
          {"width", width},
          {"height", height},
          {"frame_time", frameTime},
          {"exposure", scene.settings.exposure},
          {"spp", settings.samplesPerPixel},
          {"seed", settings.seed},
          {"pixel_jitter", settings.pixelJitter},
          {"sample_still_pixels_once", settings.sampleStillPixelsOnce},
          {"shading", shading}};
}

// The partial's header for a shard's tree as it stands.
ReferencePartial partialOf(const nlohmann::json& identity, const ReferenceSettings& settings, SampleRange shard,
                           uint64_t pixels, const ShardSumTree& tree) {
  ReferencePartial header;
  header.identity = identity;
  header.version = referencePartialVersion();
  header.samples = settings.samplesPerPixel;
  header.shardIndex = settings.shard.index;
  header.shardCount = settings.shard.count;
  header.shard = shard;
  header.samplesDone = tree.samplesDone();
  header.pixels = pixels;
  for (const ShardSumTree::Held& held : tree.held()) header.nodes.push_back(held.node);
  return header;
}

// Resumes `tree` from the checkpoint, when there is one: its held nodes' sums go to their slots.
void resumeFromCheckpoint(const std::filesystem::path& path, const ReferencePartial& expected, ShardSumTree& tree,
                          vk::Buffer& sums) {
  if (!std::filesystem::exists(path)) return;
  const ReferencePartial saved = readReferencePartial(path);
  const std::string name = "checkpoint '" + path.string() + "'";
  if (saved.identity != expected.identity)
    throw Error(name + " was made for other settings (" + saved.identity.dump() +
                "); remove it or pass another --checkpoint");
  if (saved.shardIndex != expected.shardIndex || saved.shardCount != expected.shardCount)
    throw Error(name + " holds shard " + saved.shardText() + ", not " + expected.shardText());
  if (saved.version != expected.version)
    throw Error(name + " was written by " + saved.version + ", this is " + expected.version + ": render it again");
  while (tree.samplesDone() < saved.samplesDone) tree.add();
  const std::vector<ShardSumTree::Held> held = tree.held();
  bool same = held.size() == saved.nodes.size();
  for (size_t i = 0; same && i < held.size(); ++i) same = held[i].node == saved.nodes[i];
  if (!same) throw Error(name + " is damaged: its nodes are not those of " + std::to_string(saved.samplesDone) + " samples");
  std::vector<glm::vec4> data(saved.pixels);
  for (size_t i = 0; i < held.size(); ++i) {
    readReferencePartialNode(path, saved, i, data);
    sums.write(std::as_bytes(std::span<const glm::vec4>(data)), held[i].slot * saved.pixels * sizeof(glm::vec4));
  }
}

void writeCheckpoint(const std::filesystem::path& path, const ReferencePartial& header,
                     const std::vector<ShardSumTree::Held>& held, const vk::Buffer& sums) {
  writeReferencePartial(path, header, [&](size_t i) {
    std::vector<glm::vec4> data(header.pixels);
    sums.read(std::as_writable_bytes(std::span<glm::vec4>(data)), held[i].slot * header.pixels * sizeof(glm::vec4));
    return data;
  });
}

// The fold at the end of a shard's render: its held nodes, all in slots, added in the tree's order.
FoldProgram foldOfFinishedShard(const ReferenceSettings& settings) {
  const SampleRange shard = shardSamples(settings.samplesPerPixel, settings.shard.index, settings.shard.count);
  ShardSumTree tree(settings.samplesPerPixel, shard);
  while (!tree.finished()) tree.add();
  return foldProgram(settings.samplesPerPixel, tree.held(), {}, tree.slotCount());
}

}  // namespace

std::vector<float> referenceShutterTimes(float frameTime, float exposure, uint32_t samples, uint32_t seed) {
  std::vector<float> times(samples);
  const uint32_t step = spreadingStep(samples);
  const double open = double(frameTime) - double(exposure);
  for (uint32_t k = 0; k < samples; ++k) {
    const uint32_t stratum = static_cast<uint32_t>((uint64_t(k) * step) % samples);
    const double jitter = double(splitMix64((uint64_t(seed) << 32) | stratum) >> 11) * 0x1.0p-53;
    times[k] = static_cast<float>(open + (stratum + jitter) / samples * double(exposure));
  }
  return times;
}

ReferenceStage::ReferenceStage(const vk::Context& context, const HitShading* hits)
    : context_(context),
      findMovingPixels_(context, kernels::kernel("reference/find_moving_pixels")),
      accumulate_(context, kernels::kernel("reference/accumulate_sample"), ShadingKernel::Rays::Traced,
                  hits),
      fold_(context),
      hits_(hits) {}

ReferenceStage::~ReferenceStage() = default;

void ReferenceStage::forgetTraceScene() { traceScene_.reset(); }

uint32_t ReferenceStage::cutTraces() const { return traceScene_ ? traceScene_->cutTraces() : 0u; }

namespace {

// Why every pixel must take every sample, or empty when only the pixels that something moving
// crosses need more than one.
std::string whyEveryPixelIsSampled(const scene::Scene& scene, std::span<const float> times, uint32_t width,
                                   uint32_t height, const ReferenceSettings& settings) {
  if (!settings.sampleStillPixelsOnce) return "turned off in the settings";
  if (settings.pixelJitter) return "pixel jitter takes a new point of every pixel per sample";
  if (settings.samplesPerPixel == 1) return "one sample per pixel";
  const gpu::PinholeCamera first = pinholeCamera(scene, times[0], width, height);
  for (const float t : times)
    if (!sameCamera(pinholeCamera(scene, t, width, height), first)) return "the camera moves during the shutter";
  return {};
}

}  // namespace

vk::Buffer ReferenceStage::findMovingPixels(vk::FrameRecorder& frame, const scene::Scene& scene,
                                            std::span<const float> times, uint32_t width, uint32_t height,
                                            const ReferenceSettings& settings, float tMin, float tMax,
                                            vk::FrameTimings& timings) {
  if (!whyEveryPixelIsSampled(scene, times, width, height, settings).empty())
    return vk::Buffer(context_, sizeof(uint32_t), vk::MemoryUse::Device, "reference pixel list (unused)");
  const std::vector<gpu::PinholeCamera> cameras = {pinholeCamera(scene, times[0], width, height)};
  const std::vector<glm::vec4> boxes = sweptBoxesOfMovingInstances(scene, times);
  const uint64_t pixels = uint64_t(width) * height;
  vk::Buffer list(context_, std::max<uint64_t>(pixels, 1) * sizeof(uint32_t), vk::MemoryUse::Device,
                  "reference moving pixels");
  vk::Buffer counter(context_, sizeof(uint32_t), vk::MemoryUse::Device, "reference moving pixel count");
  const uint32_t zero = 0;
  counter.upload(std::span(&zero, 1));
  if (!boxes.empty()) {
    const vk::Buffer cameraBuffer = vk::uploadedBuffer(context_, cameras, "reference camera");
    const vk::Buffer boxBuffer = vk::uploadedBuffer(context_, boxes, "moving instance boxes");
    const gpu::MovingPixelsParams params{width, height, static_cast<uint32_t>(boxes.size() / 2), 0u, tMin, tMax, 0u, 0u};
    frame.begin();
    frame.dispatch(kMovingPixels, findMovingPixels_, {{HMB_MOVING_PIXELS_BINDING_CAMERAS, &cameraBuffer},
                    {HMB_MOVING_PIXELS_BINDING_BOXES, &boxBuffer},
                    {HMB_MOVING_PIXELS_BINDING_COUNTER, &counter},
                    {HMB_MOVING_PIXELS_BINDING_LIST, &list}},
                   params,
                   {vk::groupsFor(width, HMB_MOVING_PIXELS_GROUP_X), vk::groupsFor(height, HMB_MOVING_PIXELS_GROUP_Y), 1});
    vk::appendTimings(timings, frame.submitAndWait());
  }
  progress_.movingPixels = counter.download<uint32_t>().at(0);
  return list;
}

void ReferenceStage::plan(FramePlan& plan, const scene::Scene& scene, float frameTime, uint32_t width,
                          uint32_t height, const ReferenceSettings& settings) const {
  planKeptMeshTrees(plan, kBvhMeshes, traceScene_.get(), scene);
  planDeformation(plan, scene);
  planDeformedTrees(plan, scene);
  plan.run(kBvhInstances);
  const std::vector<float> times =
      referenceShutterTimes(frameTime, scene.settings.exposure, settings.samplesPerPixel, settings.seed);
  const std::string reason = whyEveryPixelIsSampled(scene, times, width, height, settings);
  const bool anythingMoves = std::any_of(scene.instances.begin(), scene.instances.end(),
                                         [&](const scene::Instance& i) { return instanceMoves(scene, i); });
  if (!reason.empty())
    plan.skip(kMovingPixels, reason);
  else if (!anythingMoves)
    plan.skip(kMovingPixels, "nothing moves: one sample per pixel is exact");
  else
    plan.run(kMovingPixels);
  plan.run(kAccumulate);
  if (foldOfFinishedShard(settings).steps.empty())
    plan.skip(kFold, settings.shard.count > 1 ? "the shard's samples are one node of the sum tree"
                                              : "one sample per pixel: nothing to add up");
  else
    plan.run(kFold);
  plan.run(kAverage);
}

vk::FrameTimings ReferenceStage::render(vk::FrameRecorder& frame, const scene::Scene& scene, GpuScene& gpuScene,
                                        float frameTime, uint32_t width, uint32_t height,
                                        const ReferenceSettings& settings, const FramePlan& plan,
                                        const vk::Buffer& color,
                                        const std::function<void(const ReferenceProgress&)>& progress) {
  validateReferenceSettings(settings);
  const uint64_t pixels = uint64_t(width) * height;
  const uint32_t samples = settings.samplesPerPixel;
  const SampleRange shard = shardSamples(samples, settings.shard.index, settings.shard.count);
  ShardSumTree tree(samples, shard);
  const nlohmann::json identity = checkpointIdentity(scene, frameTime, width, height, settings, hits_);
  const auto header = [&] { return partialOf(identity, settings, shard, pixels, tree); };
  vk::Buffer sums(context_, tree.slotCount() * pixels * sizeof(glm::vec4), vk::MemoryUse::Device,
                  "reference sum tree");
  vk::FrameTimings total;
  // Slots start at zero: a pixel that takes only sample 0 holds zero in every node of the tree.
  frame.begin();
  frame.fill(kAccumulate, sums, 0);
  vk::appendTimings(total, frame.submitAndWait());
  progress_ = {};
  progress_.samplesTotal = shard.size();
  if (!settings.checkpoint.empty()) resumeFromCheckpoint(settings.checkpoint, header(), tree, sums);
  progress_.samplesResumed = progress_.samplesDone = tree.samplesDone();

  if (traceScene_) traceScene_->resetStatus();  // a new one starts at zero
  const std::vector<float> times = referenceShutterTimes(frameTime, scene.settings.exposure, samples, settings.seed);
  if (!tree.finished()) {
    if (const std::optional<double> meshMs =
            prepareKeptMeshTrees(traceScene_, kBvhMeshes, plan, context_, scene, frame))
      vk::appendTimings(total, {{{kBvhMeshes, *meshMs}}, *meshMs});
    TraceScene& traceScene = *traceScene_;
    const float tMin = gpuScene.camera().znear, tMax = gpuScene.camera().zfar;
    const vk::Buffer pixelList = findMovingPixels(frame, scene, times, width, height, settings, tMin, tMax, total);
    const bool shapesChange = std::any_of(scene.instances.begin(), scene.instances.end(), [&](const scene::Instance& i) {
      return i.deforms() && scene::deformationIsAnimated(scene, i);
    });
    uint32_t savedSamples = tree.samplesDone();
    while (!tree.finished()) {
      // Batches are the whole render's (every timesPerBatch samples from sample 0), whatever
      // the shard: a batch's top level, built over all its times, is the same tree in every
      // shard. A mesh whose deformation is animated has one shape per time: its trees are
      // refitted to each time's alone.
      const uint32_t first = shard.begin + tree.samplesDone();
      const uint32_t perBatch = shapesChange ? 1u : settings.timesPerBatch;
      const uint32_t batchBegin = first / perBatch * perBatch;
      const uint32_t batchEnd = std::min(batchBegin + perBatch, samples);
      const uint32_t runEnd = std::min(batchEnd, shard.end);
      const std::span<const float> batch(times.data() + batchBegin, batchEnd - batchBegin);
      if (gpuScene.deforms()) vk::appendTimings(total, traceScene.followDeformation(scene, batch[0], gpuScene, frame));
      traceScene.setShutterTimes(scene, batch, frame);
      const double bvhMs = traceScene.instanceTreeMilliseconds();
      vk::appendTimings(total, {{{kBvhInstances, bvhMs}}, bvhMs});
      std::vector<gpu::PinholeCamera> cameras;
      for (const float t : batch) cameras.push_back(pinholeCamera(scene, t, width, height));
      const vk::Buffer cameraBuffer = vk::uploadedBuffer(context_, cameras, "reference cameras");
      for (uint32_t sample = first; sample < runEnd; ++sample) {
        const SumStep step = tree.add();
        // Sample 0 covers every pixel; later ones only the moving pixels when listed.
        const bool listed = progress_.movingPixels && sample > 0;
        const uint32_t listLength = listed ? static_cast<uint32_t>(*progress_.movingPixels) : 0u;
        const gpu::ReferenceSampleParams params{
            width,
            height,
            sample - batchBegin,
            sample,
            settings.seed,
            (settings.pixelJitter ? HMB_REFERENCE_PIXEL_JITTER : 0u) | (listed ? HMB_REFERENCE_PIXEL_LIST : 0u),
            traceScene.instanceCount(),
            traceScene.timeCount(),
            tMin,
            tMax,
            listLength,
            step.foldSlot,
            step.foldLevels,
            step.targetSlot,
            0u,
            0u};
        const TraceScene& ts = traceScene;
        const glm::uvec3 groups =
            listed ? vk::foldedGroups(vk::groupsFor(listLength, HMB_REFERENCE_GROUP_X * HMB_REFERENCE_GROUP_Y))
                   : glm::uvec3(vk::groupsFor(width, HMB_REFERENCE_GROUP_X),
                                vk::groupsFor(height, HMB_REFERENCE_GROUP_Y), 1);
        frame.begin();
        if (groups.x > 0) {
          const vk::ComputeKernel& kernel = accumulate_.forScene(gpuScene, &ts);
          vk::Bindings bindings = {{HMB_REFERENCE_BINDING_CAMERAS, &cameraBuffer},
                                   {HMB_REFERENCE_BINDING_SUMS, &sums},
                                   {HMB_REFERENCE_BINDING_PIXELS, &pixelList}};
          ts.bind(bindings, HMB_REFERENCE_BINDING_TRACE_SCENE, kernel.bindsByAddress());
          gpuScene.bind(bindings, HMB_REFERENCE_BINDING_SCENE, kernel.bindsByAddress());
          frame.dispatch(kAccumulate, kernel, bindings, params, groups);
        }
        vk::appendTimings(total, frame.submitAndWait());
        progress_.pixelSamples += listed ? listLength : pixels;
        ++progress_.samplesDone;
        if (progress) progress(progress_);
      }
      // Saved every timesPerBatch samples (a deforming scene's batches are single times) and
      // at the end.
      const bool saveNow = tree.samplesDone() - savedSamples >= settings.timesPerBatch || tree.finished();
      if (!settings.checkpoint.empty() && saveNow) {
        writeCheckpoint(settings.checkpoint, header(), tree.held(), sums);
        savedSamples = tree.samplesDone();
      }
    }
  }
  const FoldProgram program = foldProgram(samples, tree.held(), {}, tree.slotCount());
  vk::appendTimings(total, fold_.run(frame, program, sums, pixels, nullptr, color));
  return total;
}

ReferenceFold::ReferenceFold(const vk::Context& context)
    : context_(context),
      fold_(context, kernels::kernel("reference/fold_sums")),
      average_(context, kernels::kernel("reference/average_samples")) {}

vk::FrameTimings ReferenceFold::run(vk::FrameRecorder& frame, const FoldProgram& program, const vk::Buffer& sums,
                                    uint64_t pixels, const std::function<void(const SumNode&, uint32_t slot)>& load,
                                    const vk::Buffer& color) const {
  if (!program.result) throw Error("reference: no samples to average");
  vk::FrameTimings timings;
  const glm::uvec3 groups = vk::foldedGroups(vk::groupsFor(static_cast<uint32_t>(pixels), HMB_FOLD_SUMS_GROUP));
  std::vector<glm::uvec4> ops;
  // The additions since the last load, in one dispatch.
  const auto addUp = [&] {
    if (ops.empty()) return;
    const vk::Buffer opBuffer = vk::uploadedBuffer(context_, ops, "reference fold steps");
    const gpu::FoldSumsParams params{static_cast<uint32_t>(pixels), static_cast<uint32_t>(ops.size()), 0u, 0u};
    frame.begin();
    frame.dispatch(ReferenceStage::kFold, fold_,
                   {{HMB_FOLD_SUMS_BINDING_SUMS, &sums}, {HMB_FOLD_SUMS_BINDING_OPS, &opBuffer}}, params, groups);
    vk::appendTimings(timings, frame.submitAndWait());
    ops.clear();
  };
  for (const FoldStep& step : program.steps) {
    if (step.kind == FoldStep::Kind::Add) {
      ops.emplace_back(step.left, step.right, 0u, 0u);
      continue;
    }
    addUp();
    load(step.node, step.left);
  }
  addUp();
  const gpu::AverageParams params{static_cast<uint32_t>(pixels), *program.result, 0u, 0u};
  frame.begin();
  frame.dispatch(ReferenceStage::kAverage, average_, {{HMB_AVERAGE_BINDING_SUMS, &sums}, {HMB_AVERAGE_BINDING_COLOR, &color}},
                 params, vk::foldedGroups(vk::groupsFor(static_cast<uint32_t>(pixels), HMB_REFERENCE_AVERAGE_GROUP)));
  vk::appendTimings(timings, frame.submitAndWait());
  return timings;
}

}  // namespace hmb::passes
