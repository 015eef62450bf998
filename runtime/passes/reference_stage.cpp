#include "runtime/passes/reference_stage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "hmblur/context.h"
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

// The partial's header for a shard that took `done` samples and holds `nodes`.
ReferencePartial partialOf(const nlohmann::json& identity, const ReferenceSettings& settings, SampleRange shard,
                           uint64_t pixels, uint32_t done, std::vector<SumNode> nodes) {
  ReferencePartial header;
  header.identity = identity;
  header.version = referencePartialVersion();
  header.samples = settings.samplesPerPixel;
  header.shardIndex = settings.shard.index;
  header.shardCount = settings.shard.count;
  header.shard = shard;
  header.samplesDone = done;
  header.pixels = pixels;
  header.nodes = std::move(nodes);
  return header;
}

// Resumes from the checkpoint, when there is one: its nodes go onto the stack as they are.
// Returns the samples it took.
uint32_t resumeFromCheckpoint(const std::filesystem::path& path, const ReferencePartial& expected, SumStack& stack) {
  if (!std::filesystem::exists(path)) return 0;
  const ReferencePartial saved = readReferencePartial(path);
  const std::string name = "checkpoint '" + path.string() + "'";
  if (saved.identity != expected.identity)
    throw Error(name + " was made for other settings (" + saved.identity.dump() +
                "); remove it or pass another --checkpoint");
  if (saved.shardIndex != expected.shardIndex || saved.shardCount != expected.shardCount)
    throw Error(name + " holds shard " + saved.shardText() + ", not " + expected.shardText());
  if (saved.version != expected.version)
    throw Error(name + " was written by " + saved.version + ", this is " + expected.version + ": render it again");
  for (size_t i = 0; i < saved.nodes.size(); ++i) {
    std::vector<glm::vec4> sums(saved.pixels);
    readReferencePartialNode(path, saved, i, sums);
    stack.push(saved.nodes[i], std::move(sums), false);
  }
  return saved.samplesDone;
}

void writeCheckpoint(const std::filesystem::path& path, const ReferencePartial& header, const SumStack& stack) {
  writeReferencePartial(path, header, [&](size_t i) { return stack.sumsOf(i); });
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
      sumKernels_(context),
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
  // Sums held in host memory are added on the device as they come back, so any shard of more
  // than one sample may add.
  if (shardSamples(settings.samplesPerPixel, settings.shard.index, settings.shard.count).size() == 1)
    plan.skip(kFold, "one sample: nothing to add up");
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
  const nlohmann::json identity = checkpointIdentity(scene, frameTime, width, height, settings, hits_);
  vk::FrameTimings total;
  DeviceSumSlots slots(context_, frame, sumKernels_, width, height, total);
  SumStack stack(slots);
  uint32_t done = 0;
  const auto header = [&] { return partialOf(identity, settings, shard, pixels, done, stack.nodes()); };
  progress_ = {};
  progress_.samplesTotal = shard.size();
  if (!settings.checkpoint.empty()) done = resumeFromCheckpoint(settings.checkpoint, header(), stack);
  progress_.samplesResumed = progress_.samplesDone = done;

  if (traceScene_) traceScene_->resetStatus();  // a new one starts at zero
  const std::vector<float> times = referenceShutterTimes(frameTime, scene.settings.exposure, samples, settings.seed);
  if (done < shard.size()) {
    if (const std::optional<double> meshMs =
            prepareKeptMeshTrees(traceScene_, kBvhMeshes, plan, context_, scene, frame))
      vk::appendTimings(total, {{{kBvhMeshes, *meshMs}}, *meshMs});
    TraceScene& traceScene = *traceScene_;
    const float tMin = gpuScene.camera().znear, tMax = gpuScene.camera().zfar;
    const vk::Buffer pixelList = findMovingPixels(frame, scene, times, width, height, settings, tMin, tMax, total);
    if (progress_.movingPixels) {
      // Samples after the first write the listed pixels alone: the others must hold zero in
      // every node but sample 0's, so the slots start at zero.
      frame.begin();
      for (const DeviceSumSlots::Band& band : slots.bands()) frame.fill(kAccumulate, band.sums, 0);
      vk::appendTimings(total, frame.submitAndWait());
    }
    const bool shapesChange = std::any_of(scene.instances.begin(), scene.instances.end(), [&](const scene::Instance& i) {
      return i.deforms() && scene::deformationIsAnimated(scene, i);
    });
    uint32_t savedSamples = done;
    while (done < shard.size()) {
      // Batches are the whole render's (every timesPerBatch samples from sample 0), whatever
      // the shard: a batch's top level, built over all its times, is the same tree in every
      // shard. A mesh whose deformation is animated has one shape per time: its trees are
      // refitted to each time's alone.
      const uint32_t first = shard.begin + done;
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
        const SumStack::SampleStep step = stack.beginSample(sample);
        glm::uvec4 foldSlots[2] = {glm::uvec4(0u), glm::uvec4(0u)};
        for (size_t i = 0; i < step.fold.size(); ++i) foldSlots[i / 4][i % 4] = step.fold[i];
        // Sample 0 covers every pixel; later ones only the moving pixels when listed.
        const bool listed = progress_.movingPixels && sample > 0;
        const uint32_t listLength = listed ? static_cast<uint32_t>(*progress_.movingPixels) : 0u;
        // One dispatch a band of the sums: a band's invocations cover its rows (or the whole
        // list, keeping the pixels of its rows).
        frame.begin();
        for (const DeviceSumSlots::Band& band : slots.bands()) {
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
              static_cast<uint32_t>(step.fold.size()),
              step.target,
              band.firstRow,
              band.rows,
              0u,
              {foldSlots[0], foldSlots[1]}};
          const glm::uvec3 groups =
              listed ? vk::foldedGroups(vk::groupsFor(listLength, HMB_REFERENCE_GROUP_X * HMB_REFERENCE_GROUP_Y))
                     : glm::uvec3(vk::groupsFor(width, HMB_REFERENCE_GROUP_X),
                                  vk::groupsFor(band.rows, HMB_REFERENCE_GROUP_Y), 1);
          if (groups.x == 0) continue;
          const TraceScene& ts = traceScene;
          const vk::ComputeKernel& kernel = accumulate_.forScene(gpuScene, &ts);
          vk::Bindings bindings = {{HMB_REFERENCE_BINDING_CAMERAS, &cameraBuffer},
                                   {HMB_REFERENCE_BINDING_SUMS, &band.sums},
                                   {HMB_REFERENCE_BINDING_PIXELS, &pixelList}};
          ts.bind(bindings, HMB_REFERENCE_BINDING_TRACE_SCENE, kernel.bindsByAddress());
          gpuScene.bind(bindings, HMB_REFERENCE_BINDING_SCENE, kernel.bindsByAddress());
          frame.dispatch(kAccumulate, kernel, bindings, params, groups);
        }
        vk::appendTimings(total, frame.submitAndWait());
        stack.finishSample();
        progress_.samplesDone = ++done;
        progress_.pixelSamples += listed ? listLength : pixels;
        if (progress) progress(progress_);
      }
      // Saved every timesPerBatch samples (a deforming scene's batches are single times) and
      // at the end.
      const bool saveNow = done - savedSamples >= settings.timesPerBatch || done == shard.size();
      if (!settings.checkpoint.empty() && saveNow) {
        writeCheckpoint(settings.checkpoint, header(), stack);
        savedSamples = done;
      }
    }
  }
  slots.average(stack.total(), color);
  return total;
}

ReferenceSumKernels::ReferenceSumKernels(const vk::Context& context)
    : fold(context, kernels::kernel("reference/fold_sums")), average(context, kernels::kernel("reference/average_samples")) {}

DeviceSumSlots::DeviceSumSlots(const vk::Context& context, vk::FrameRecorder& frame, const ReferenceSumKernels& kernels,
                               uint32_t width, uint32_t height, vk::FrameTimings& timings)
    : context_(context), frame_(frame), kernels_(kernels), width_(width), timings_(timings) {
  const uint64_t slotBytes = std::max<uint64_t>(uint64_t(width) * height * sizeof(glm::vec4), 1);
  const uint64_t range = context.info().maxStorageBufferRange;
  count_ = static_cast<uint32_t>(std::clamp<uint64_t>(kDeviceBytes / slotBytes, kMinSlots, kMaxSlots));
  // One band where one buffer holds enough slots: a band more costs a dispatch more a sample.
  if (range / slotBytes >= kMinSlots) count_ = static_cast<uint32_t>(std::min<uint64_t>(count_, range / slotBytes));
  const uint64_t rowBytes = uint64_t(count_) * width * sizeof(glm::vec4);
  const uint64_t rowsPerBand = std::min<uint64_t>(range / rowBytes, height);
  if (rowsPerBand == 0)
    throw Error("the reference's " + std::to_string(count_) + " sums of a row of " + std::to_string(width) +
                " pixels do not fit in one of the device's storage buffers (" +
                std::to_string(range >> 20) + " MiB): use a narrower image");
  const uint32_t bandCount = static_cast<uint32_t>((height + rowsPerBand - 1) / rowsPerBand);
  for (uint32_t b = 0; b < bandCount; ++b) {
    // Bands as even as they go.
    const uint32_t first = static_cast<uint32_t>(uint64_t(height) * b / bandCount);
    const uint32_t rows = static_cast<uint32_t>(uint64_t(height) * (b + 1) / bandCount) - first;
    bands_.push_back({first, rows, vk::Buffer(context, uint64_t(count_) * rows * width * sizeof(glm::vec4),
                                              vk::MemoryUse::Device, "reference sums")});
  }
}

void DeviceSumSlots::upload(uint32_t slot, std::span<const glm::vec4> sums) {
  for (Band& band : bands_)
    band.sums.write(std::as_bytes(sums.subspan(uint64_t(band.firstRow) * width_, bandPixels(band))),
                    offsetOf(band, slot));
}

std::vector<glm::vec4> DeviceSumSlots::download(uint32_t slot) {
  std::vector<glm::vec4> sums;
  for (const Band& band : bands_) {
    std::vector<glm::vec4> part(bandPixels(band));
    band.sums.read(std::as_writable_bytes(std::span<glm::vec4>(part)), offsetOf(band, slot));
    sums.insert(sums.end(), part.begin(), part.end());
  }
  return sums;
}

void DeviceSumSlots::clear(uint32_t slot) {
  for (Band& band : bands_)
    band.sums.write(std::as_bytes(std::span<const glm::vec4>(std::vector<glm::vec4>(bandPixels(band), glm::vec4(0.0f)))),
                    offsetOf(band, slot));
}

void DeviceSumSlots::add(std::span<const glm::uvec2> pairs) {
  std::vector<glm::uvec4> ops;
  for (const glm::uvec2& p : pairs) ops.emplace_back(p.x, p.y, 0u, 0u);
  const vk::Buffer opBuffer = vk::uploadedBuffer(context_, ops, "reference sum pairs");
  frame_.begin();
  for (const Band& band : bands_) {
    const uint32_t pixels = static_cast<uint32_t>(bandPixels(band));
    const gpu::FoldSumsParams params{pixels, static_cast<uint32_t>(ops.size()), 0u, 0u};
    frame_.dispatch(ReferenceStage::kFold, kernels_.fold,
                    {{HMB_FOLD_SUMS_BINDING_SUMS, &band.sums}, {HMB_FOLD_SUMS_BINDING_OPS, &opBuffer}}, params,
                    vk::foldedGroups(vk::groupsFor(pixels, HMB_FOLD_SUMS_GROUP)));
  }
  vk::appendTimings(timings_, frame_.submitAndWait());
}

void DeviceSumSlots::average(uint32_t slot, const vk::Buffer& color) {
  frame_.begin();
  for (const Band& band : bands_) {
    const uint32_t pixels = static_cast<uint32_t>(bandPixels(band));
    const gpu::AverageParams params{pixels, slot, band.firstRow * width_, 0u};
    frame_.dispatch(ReferenceStage::kAverage, kernels_.average,
                    {{HMB_AVERAGE_BINDING_SUMS, &band.sums}, {HMB_AVERAGE_BINDING_COLOR, &color}}, params,
                    vk::foldedGroups(vk::groupsFor(pixels, HMB_REFERENCE_AVERAGE_GROUP)));
  }
  vk::appendTimings(timings_, frame_.submitAndWait());
}

}  // namespace hmb::passes
