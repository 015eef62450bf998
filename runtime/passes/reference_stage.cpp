#include "runtime/passes/reference_stage.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/manifest.h"
#include "kernels/reference/reference_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/deformed_vertices.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "scenes/deformation.h"

namespace hmb::passes {
namespace {

constexpr char kCheckpointMagic[8] = {'H', 'M', 'B', 'R', 'E', 'F', '1', '\0'};

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


// What a checkpoint must match to be resumed: the scene, the image and every setting that
// changes which samples are taken.
nlohmann::json checkpointIdentity(const scene::Scene& scene, float frameTime, uint32_t width, uint32_t height,
                                  const ReferenceSettings& settings) {
  return {{"scene", scene.name},
          {"triangles", scene.triangleCount()},
          {"instances", scene.instances.size()},
          {"width", width},
          {"height", height},
          {"frame_time", frameTime},
          {"exposure", scene.settings.exposure},
          {"spp", settings.samplesPerPixel},
          {"seed", settings.seed},
          {"pixel_jitter", settings.pixelJitter}};
}

// Reads the samples done and the per-pixel sums; 0 when there is no file yet.
uint32_t readCheckpoint(const std::filesystem::path& path, const nlohmann::json& identity,
                        std::vector<glm::vec4>& sums) {
  if (!std::filesystem::exists(path)) return 0;
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  uint64_t headerBytes = 0;
  in.read(magic, sizeof(magic));
  in.read(reinterpret_cast<char*>(&headerBytes), sizeof(headerBytes));
  if (!in || std::memcmp(magic, kCheckpointMagic, sizeof(magic)) != 0 || headerBytes > (1u << 20))
    throw Error("checkpoint '" + path.string() + "' is not a reference checkpoint");
  std::string text(headerBytes, '\0');
  in.read(text.data(), static_cast<std::streamsize>(headerBytes));
  const nlohmann::json header = nlohmann::json::parse(text, nullptr, false);
  if (!in || header.is_discarded() || !header.contains("identity") || !header.contains("samples_done"))
    throw Error("checkpoint '" + path.string() + "' is damaged");
  if (header["identity"] != identity)
    throw Error("checkpoint '" + path.string() + "' was made for other settings (" + header["identity"].dump() +
                "); remove it or pass another --checkpoint");
  in.read(reinterpret_cast<char*>(sums.data()), static_cast<std::streamsize>(sums.size() * sizeof(glm::vec4)));
  if (!in) throw Error("checkpoint '" + path.string() + "' is truncated");
  return header["samples_done"].get<uint32_t>();
}

// Written beside the target and renamed over it, so an interrupted write never loses the last one.
void writeCheckpoint(const std::filesystem::path& path, const nlohmann::json& identity, uint32_t samplesDone,
                     const std::vector<glm::vec4>& sums) {
  const std::string header = nlohmann::json{{"identity", identity}, {"samples_done", samplesDone}}.dump();
  const uint64_t headerBytes = header.size();
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(kCheckpointMagic, sizeof(kCheckpointMagic));
    out.write(reinterpret_cast<const char*>(&headerBytes), sizeof(headerBytes));
    out.write(header.data(), static_cast<std::streamsize>(header.size()));
    out.write(reinterpret_cast<const char*>(sums.data()), static_cast<std::streamsize>(sums.size() * sizeof(glm::vec4)));
    if (!out) throw Error("cannot write checkpoint '" + partial.string() + "'");
  }
  std::filesystem::rename(partial, path);
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
      average_(context, kernels::kernel("reference/average_samples")) {}

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
  plan.run(kAverage);
}

vk::FrameTimings ReferenceStage::render(vk::FrameRecorder& frame, const scene::Scene& scene, GpuScene& gpuScene,
                                        float frameTime, uint32_t width, uint32_t height,
                                        const ReferenceSettings& settings, const FramePlan& plan,
                                        const vk::Buffer& color,
                                        const std::function<void(const ReferenceProgress&)>& progress) {
  validateReferenceSettings(settings);
  const uint64_t pixels = uint64_t(width) * height;
  const nlohmann::json identity = checkpointIdentity(scene, frameTime, width, height, settings);
  std::vector<glm::vec4> sums(pixels, glm::vec4(0.0f));
  progress_ = {};
  progress_.samplesTotal = settings.samplesPerPixel;
  if (!settings.checkpoint.empty()) progress_.samplesResumed = readCheckpoint(settings.checkpoint, identity, sums);
  progress_.samplesDone = std::min(progress_.samplesResumed, settings.samplesPerPixel);
  vk::Buffer sum(context_, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "reference sums");
  sum.upload(std::span<const glm::vec4>(sums));

  vk::FrameTimings total;
  if (traceScene_) traceScene_->resetStatus();  // a new one starts at zero
  const std::vector<float> times =
      referenceShutterTimes(frameTime, scene.settings.exposure, settings.samplesPerPixel, settings.seed);
  if (progress_.samplesDone < settings.samplesPerPixel) {
    if (const std::optional<double> meshMs =
            prepareKeptMeshTrees(traceScene_, kBvhMeshes, plan, context_, scene, frame))
      vk::appendTimings(total, {{{kBvhMeshes, *meshMs}}, *meshMs});
    TraceScene& traceScene = *traceScene_;
    const float tMin = gpuScene.camera().znear, tMax = gpuScene.camera().zfar;
    const vk::Buffer pixelList = findMovingPixels(frame, scene, times, width, height, settings, tMin, tMax, total);
    const bool shapesChange = std::any_of(scene.instances.begin(), scene.instances.end(), [&](const scene::Instance& i) {
      return i.deforms() && scene::deformationIsAnimated(scene, i);
    });
    uint32_t savedSamples = progress_.samplesDone;
    while (progress_.samplesDone < settings.samplesPerPixel) {
      const uint32_t first = progress_.samplesDone;
      // A mesh whose deformation is animated has one shape per time: its trees are refitted to
      // each time's alone.
      const uint32_t perBatch = shapesChange ? 1u : settings.timesPerBatch;
      const uint32_t count = std::min(perBatch, settings.samplesPerPixel - first);
      const std::span<const float> batch(times.data() + first, count);
      if (gpuScene.deforms()) vk::appendTimings(total, traceScene.followDeformation(scene, batch[0], gpuScene, frame));
      traceScene.setShutterTimes(scene, batch, frame);
      const double bvhMs = traceScene.instanceTreeMilliseconds();
      vk::appendTimings(total, {{{kBvhInstances, bvhMs}}, bvhMs});
      std::vector<gpu::PinholeCamera> cameras;
      for (const float t : batch) cameras.push_back(pinholeCamera(scene, t, width, height));
      const vk::Buffer cameraBuffer = vk::uploadedBuffer(context_, cameras, "reference cameras");
      for (uint32_t i = 0; i < count; ++i) {
        // The first sample covers every pixel; later ones only the moving pixels when listed.
        const bool listed = progress_.movingPixels && first + i > 0;
        const uint32_t listLength = listed ? static_cast<uint32_t>(*progress_.movingPixels) : 0u;
        const gpu::ReferenceSampleParams params{
            width,
            height,
            i,
            first + i,
            settings.seed,
            (settings.pixelJitter ? HMB_REFERENCE_PIXEL_JITTER : 0u) | (listed ? HMB_REFERENCE_PIXEL_LIST : 0u),
            traceScene.instanceCount(),
            traceScene.timeCount(),
            tMin,
            tMax,
            listLength,
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
                                   {HMB_REFERENCE_BINDING_SUM, &sum},
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
      const bool saveNow = progress_.samplesDone - savedSamples >= settings.timesPerBatch ||
                           progress_.samplesDone == settings.samplesPerPixel;
      if (!settings.checkpoint.empty() && saveNow) {
        writeCheckpoint(settings.checkpoint, identity, progress_.samplesDone, sum.download<glm::vec4>());
        savedSamples = progress_.samplesDone;
      }
    }
  }

  const gpu::AverageParams params{static_cast<uint32_t>(pixels), 0u, 0u, 0u};
  frame.begin();
  frame.dispatch(kAverage, average_, {{HMB_AVERAGE_BINDING_SUM, &sum}, {HMB_AVERAGE_BINDING_COLOR, &color}}, params,
                 vk::foldedGroups(vk::groupsFor(static_cast<uint32_t>(pixels), HMB_REFERENCE_AVERAGE_GROUP)));
  vk::appendTimings(total, frame.submitAndWait());
  return total;
}

}  // namespace hmb::passes
