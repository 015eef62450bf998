#include "runtime/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "runtime/error.h"
#include "runtime/gpu_scene.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/hybrid_stage.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/passes/reference_stage.h"
#include "runtime/passes/test_pattern_pass.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/context.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {
namespace {

io::ImageLayer vec4Layer(const std::string& name, std::vector<std::string> channels,
                         const std::vector<glm::vec4>& values) {
  io::ImageLayer layer{name, std::move(channels), false, {}, {}};
  const size_t n = layer.channels.size();
  layer.values.reserve(values.size() * n);
  for (const glm::vec4& v : values)
    for (size_t c = 0; c < n; ++c) layer.values.push_back(v[int(c)]);
  return layer;
}

io::Rgba8Image downloadDisplay(const vk::Buffer& display, uint32_t width, uint32_t height) {
  const auto packed = display.download<uint32_t>();
  io::Rgba8Image image;
  image.width = width;
  image.height = height;
  image.pixels.resize(size_t(width) * height * 4);
  std::memcpy(image.pixels.data(), packed.data(), image.pixels.size());
  return image;
}

}  // namespace

struct Renderer::Passes {
  explicit Passes(const vk::Context& context)
      : testPattern(context),
        encodeDisplay(context),
        gbuffer(context, passes::defaultVisibilityScheme(context.info())),
        reference(context),
        postProcess(context, passes::PostProcessSettings{}),
        hybrid(context, postProcess),
        recorder(context) {}
  passes::TestPatternPass testPattern;
  passes::EncodeDisplayPass encodeDisplay;
  passes::GBufferStage gbuffer;
  passes::ReferenceStage reference;
  passes::PostProcessStage postProcess;
  passes::HybridStage hybrid;
  vk::FrameRecorder recorder;
};

const std::vector<std::string>& methodNames() {
  static const std::vector<std::string> names = {"sharp", "postprocess", "hybrid", "reference"};
  return names;
}

const std::vector<std::string>& debugMethodNames() {
  static const std::vector<std::string> names = {"test-pattern"};
  return names;
}

namespace {

// The user's choices over `s`, validated (hmb::Error names the first absurd value).
passes::PostProcessSettings withChoices(passes::PostProcessSettings s, const PostProcessChoices& c) {
  if (c.filter) s.filter = passes::parseFilter(*c.filter);
  if (c.range) s.range = passes::parseRange(*c.range);
  if (c.samples) s.samples = *c.samples;
  if (c.tileSize) {
    s.tileSize = *c.tileSize;
    s.jimenezTileSize = *c.tileSize;
  }
  if (c.neighborhood) s.neighborhood = *c.neighborhood;
  if (c.foregroundBoost) s.foregroundBoost = *c.foregroundBoost;
  if (c.softZExtent) s.softZExtent = *c.softZExtent;
  if (c.seed) s.seed = *c.seed;
  passes::validate(s);
  return s;
}

}  // namespace

passes::PostProcessSettings postProcessSettingsFor(const scene::Scene& scene, const RenderSettings& settings) {
  passes::PostProcessSettings base = passes::PostProcessSettings::fromScene(scene.settings);
  // The paper's tile sizes are pixels of a 720-line image; velocities in pixels scale with the
  // image, so the tiles do too (else a small image is a handful of tiles and every blur spills
  // over the whole frame).
  const float linesScale = float(settings.height) / 720.0f;
  base.tileSize = std::max(1u, static_cast<uint32_t>(std::lround(float(base.tileSize) * linesScale)));
  base.jimenezTileSize = std::max(1u, static_cast<uint32_t>(std::lround(float(base.jimenezTileSize) * linesScale)));
  return withChoices(base, settings.postprocess);
}

passes::HybridSettings hybridSettingsFor(const scene::Scene& scene, const RenderSettings& settings) {
  passes::HybridSettings s = passes::HybridSettings::fromScene(scene.settings);
  const HybridChoices& c = settings.hybrid;
  if (c.edgeThreshold) s.edgeThreshold = *c.edgeThreshold;
  if (c.stop) s.stop = passes::parseRevealStop(*c.stop);
  if (c.maxRecursion) s.maxRecursion = *c.maxRecursion;
  if (c.luminanceThreshold) s.luminanceThreshold = *c.luminanceThreshold;
  if (c.composite) s.composite = passes::parseComposite(*c.composite);
  if (c.maskBackgroundBoost) s.maskBackgroundBoost = *c.maskBackgroundBoost;
  if (c.maskForegroundDivide) s.maskForegroundDivide = *c.maskForegroundDivide;
  passes::validate(s);
  return s;
}

void validateRenderSettings(const RenderSettings& settings) {
  std::vector<std::string> names = methodNames();
  names.insert(names.end(), debugMethodNames().begin(), debugMethodNames().end());
  if (std::find(names.begin(), names.end(), settings.method) == names.end()) {
    std::string list;
    for (const auto& name : names) list += (list.empty() ? "" : ", ") + name;
    throw Error("unknown method '" + settings.method + "'; available: " + list);
  }
  if (settings.width == 0 || settings.height == 0)
    throw Error("image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                " is empty; width and height must be at least 1");
  if (settings.width > kMaxImageSide || settings.height > kMaxImageSide)
    throw Error("image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                " exceeds the limit of " + std::to_string(kMaxImageSide) + " pixels per side");
  if (settings.frameTime && !std::isfinite(*settings.frameTime))
    throw Error("frame time must be a finite number of seconds");
  if (settings.method == "reference") passes::validateReferenceSettings(settings.reference);
  if (settings.method == "postprocess" || settings.method == "hybrid")
    withChoices(passes::PostProcessSettings{}, settings.postprocess);
  if (settings.method == "hybrid") {
    if (settings.postprocess.filter && *settings.postprocess.filter != "mcguire")
      throw Error("the hybrid method blurs with the McGuire filter (--filter mcguire)");
    const passes::HybridSettings hybrid = hybridSettingsFor(scene::Scene{}, settings);
    if (hybrid.composite == passes::HybridComposite::Coverage && settings.postprocess.range &&
        passes::parseRange(*settings.postprocess.range) != passes::GatherRange::Adapted)
      throw Error("the hybrid method's coverage composite needs the adapted range (--range adapted)");
  }
}

Renderer::Renderer(vk::Context& context) : context_(context) {}
Renderer::~Renderer() = default;

RenderResult Renderer::render(const scene::Scene& scene, const RenderSettings& settings) {
  validateRenderSettings(settings);
  if (!passes_) passes_ = std::make_unique<Passes>(context_);

  context_.resetMemoryPeak();
  RenderResult result;
  result.method = settings.method;
  result.settings = settings;
  result.settings.onProgress = nullptr;
  result.width = settings.width;
  result.height = settings.height;
  result.frameTime = settings.frameTime.value_or(scene.settings.frameTime);
  const uint32_t width = settings.width, height = settings.height;
  const uint64_t pixels = uint64_t(width) * height;
  vk::Buffer display(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "display (RGBA8)");
  vk::FrameRecorder& frame = passes_->recorder;
  vk::FrameTimings timings;

  if (settings.method == "test-pattern") {
    // The test pattern proves the runtime; it does not read the scene.
    vk::Buffer linear(context_, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "beauty (linear RGBA)");
    result.plan.run(passes::TestPatternPass::kName);
    result.plan.run(passes::EncodeDisplayPass::kName);
    frame.begin();
    passes_->testPattern.record(frame, linear, width, height, result.frameTime);
    passes_->encodeDisplay.record(frame, linear, display, width, height);
    timings = frame.submitAndWait();
    result.image = {width, height, {vec4Layer("", {"R", "G", "B", "A"}, linear.download<glm::vec4>())}};
  } else if (settings.method == "reference") {
    // Distributed ray tracing over the shutter: the judge of every other method.
    GpuScene gpuScene(context_, scene);
    gpuScene.setFrame(scene, result.frameTime, width, height);
    if (!settings.skipUnneededPasses) gpuScene.keepTexturePath();
    vk::Buffer linear(context_, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "beauty (linear RGBA)");
    if (!(settings.skipUnneededPasses && settings.reuseAcrossFrames)) passes_->reference.forgetTraceScene();
    passes_->reference.plan(result.plan, scene, result.frameTime, width, height, settings.reference);
    passes::planTexturePath(result.plan, gpuScene);
    result.plan.run(passes::EncodeDisplayPass::kName);
    timings = passes_->reference.render(frame, scene, gpuScene, result.frameTime, width, height, settings.reference,
                                        result.plan, linear, settings.onProgress);
    frame.begin();
    passes_->encodeDisplay.record(frame, linear, display, width, height);
    vk::appendTimings(timings, frame.submitAndWait());
    result.reference = passes_->reference.lastProgress();
    result.image = {width, height, {vec4Layer("", {"R", "G", "B", "A"}, linear.download<glm::vec4>())}};
  } else {
    // sharp: the G-buffer's shaded colour, the shutter-close instant without blur.
    // postprocess: that colour blurred along the G-buffer's velocities (tile-max, neighbour-max, gather).
    GpuScene gpuScene(context_, scene);
    gpuScene.setFrame(scene, result.frameTime, width, height);
    if (!settings.skipUnneededPasses) gpuScene.keepTexturePath();
    passes::GBufferStage& gbuffer = passes_->gbuffer;
    gbuffer.prepare(gpuScene, width, height);
    gbuffer.plan(result.plan);
    // With nothing moving on screen every velocity is 0: the gather returns each pixel's own
    // colour and the hybrid's mask is empty, so the blur's passes are left out.
    const bool blurMethod = settings.method == "postprocess" || settings.method == "hybrid";
    const bool still = blurMethod && settings.skipUnneededPasses && !anythingMovesOnScreen(scene, result.frameTime);
    const bool hybrid = settings.method == "hybrid" && !still;
    const bool blur = blurMethod && !still;
    vk::Buffer blurred;
    if (settings.method == "hybrid") {
      result.hybrid.emplace();
      result.hybrid->settings = hybridSettingsFor(scene, settings);
    }
    if (blurMethod) result.postprocess = postProcessSettingsFor(scene, settings);
    if (result.hybrid) {
      result.postprocess->maskBackgroundBoost = result.hybrid->settings.maskBackgroundBoost;
      result.postprocess->maskForegroundDivide = result.hybrid->settings.maskForegroundDivide;
      if (!settings.postprocess.foregroundBoost) result.postprocess->foregroundBoost = result.hybrid->settings.foregroundBoost;
    }
    if (blurMethod) {
      passes_->postProcess.configure(*result.postprocess);
      FramePlan blurPlan;
      if (settings.method == "hybrid" && !(settings.skipUnneededPasses && settings.reuseAcrossFrames))
        passes_->hybrid.forgetTraceScene();
      if (settings.method == "hybrid")
        passes_->hybrid.plan(blurPlan, scene, result.frameTime);
      else
        passes_->postProcess.plan(blurPlan);
      for (const PlannedPass& pass : blurPlan.passes()) {
        if (still)
          result.plan.skip(pass.name, "nothing moves on screen at this frame: every velocity is 0, so the blur "
                                      "returns the sharp colour");
        else if (pass.run)
          result.plan.run(pass.name);
        else
          result.plan.skip(pass.name, pass.reason);
      }
    }
    passes::planTexturePath(result.plan, gpuScene);
    if (blur) {
      passes_->postProcess.prepare(width, height);
      blurred = vk::Buffer(context_, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "post-process colour");
    }
    if (hybrid) {
      // The trace scene's mesh trees (setup, reported apart) and its instance tree at the frame
      // time (part of the frame) are built where the plan runs them, kept where it skips them.
      const auto prepared =
          passes_->hybrid.prepare(frame, scene, result.frameTime, width, height, result.hybrid->settings, result.plan);
      result.hybrid->setupMilliseconds = prepared.setup.frameMilliseconds;
      timings = prepared.frame;
      // The setup passes are listed with their times, but not added to the frame's.
      timings.passes.insert(timings.passes.begin(), prepared.setup.passes.begin(), prepared.setup.passes.end());
    }
    const vk::Buffer& beauty = blur ? blurred : gbuffer.color();
    result.plan.run(passes::EncodeDisplayPass::kName);
    vk::appendTimings(timings, passes::submitUntilRasterFits(frame, gbuffer.rasterizer(), [&](vk::FrameRecorder& f) {
      gbuffer.record(f, gpuScene);
      const passes::MotionBlurInputs layer{&gbuffer.color(), &gbuffer.normalDepth(), &gbuffer.velocity(), width,
                                           height};
      if (hybrid)
        passes_->hybrid.record(f, gbuffer, gpuScene, blurred);
      else if (blur)
        passes_->postProcess.record(f, layer, blurred);
      passes_->encodeDisplay.record(f, beauty, display, width, height);
    }));
    result.memory.gbufferBytesPerPixel = gbuffer.bytesPerPixel(width, height);
    if (const auto trees = hybrid ? passes_->hybrid.meshTreeBytes() : std::nullopt) {
      result.memory.bvhAllocatedBytesPerTriangle = trees->allocatedPerTriangle;
      result.memory.bvhBuiltBytesPerTriangle = trees->usedPerTriangle;
    }
    result.visibilityScheme = passes::visibilitySchemeName(gbuffer.rasterizer().scheme());
    result.raster = gbuffer.rasterizer().stats();

    const auto normalDepth = gbuffer.normalDepth().download<glm::vec4>();
    std::vector<glm::vec4> depth(normalDepth.size());
    for (size_t i = 0; i < depth.size(); ++i) depth[i].x = normalDepth[i].w;
    std::vector<glm::vec4> velocity;
    for (const glm::vec2& v : gbuffer.velocity().download<glm::vec2>()) velocity.emplace_back(v, 0.0f, 0.0f);
    io::ImageLayer objectId{"objectId", {"id"}, true, {}, gbuffer.objectId().download<uint32_t>()};
    objectId.ids.resize(pixels);
    result.image = {width,
                    height,
                    {vec4Layer("", {"R", "G", "B", "A"}, beauty.download<glm::vec4>()),
                     vec4Layer("depth", {"Z"}, depth), vec4Layer("normal", {"X", "Y", "Z"}, normalDepth),
                     vec4Layer("velocity", {"X", "Y"}, velocity), std::move(objectId)}};
    if (settings.method == "hybrid") {
      // The ray mask, and what the reveal found behind the pixels it traced (black elsewhere),
      // its depth and object; all empty when the frame is still and the passes were skipped.
      std::vector<uint32_t> mask(pixels, 0u), revealedId(pixels, 0u);
      std::vector<glm::vec4> revealed(pixels, glm::vec4(0.0f)), revealedDepth(pixels, glm::vec4(0.0f));
      if (hybrid) {
        const passes::RayMaskCounts counts = passes_->hybrid.rayMask().counts();
        result.hybrid->edgeCandidates = counts.edgeCandidates;
        result.hybrid->maskPixels = counts.maskPixels;
        result.hybrid->revealedPixels = counts.listedPixels;
        result.hybrid->revealRays = counts.revealRays;
        mask = passes_->hybrid.rayMask().mask().download<uint32_t>();
        mask.resize(pixels);
        const passes::ImageLayer& layer = passes_->hybrid.revealed();
        const std::vector<glm::vec4> revealedAll = layer.color().download<glm::vec4>();
        const std::vector<glm::vec4> normalDepthAll = layer.normalDepth().download<glm::vec4>();
        const std::vector<uint32_t> idAll = layer.objectId().download<uint32_t>();
        std::vector<uint32_t> traced = passes_->hybrid.rayMask().list().download<uint32_t>();
        traced.resize(std::min<size_t>(traced.size(), counts.listedPixels));
        for (const uint32_t i : traced) {
          if (i >= pixels) continue;
          revealed[i] = revealedAll[i];
          revealedDepth[i] = glm::vec4(normalDepthAll[i].w, 0.0f, 0.0f, 0.0f);
          revealedId[i] = idAll[i];
        }
      }
      result.image.layers.push_back(io::ImageLayer{"rayMask", {"mask"}, true, {}, std::move(mask)});
      result.image.layers.push_back(vec4Layer("revealed", {"R", "G", "B"}, revealed));
      result.image.layers.push_back(vec4Layer("revealedDepth", {"Z"}, revealedDepth));
      result.image.layers.push_back(io::ImageLayer{"revealedObjectId", {"id"}, true, {}, std::move(revealedId)});
    }
  }

  result.plan.attachTimings(timings);
  if (result.hybrid && result.plan.runs(passes::RevealPass::kName)) {
    // The mask is made on the device, so these passes are recorded every frame and sized from
    // it: when it is empty they dispatch no groups, and the report says so.
    if (result.hybrid->edgeCandidates == 0)
      result.plan.noteNoWork(passes::RayMaskStage::kEdges, "no pixel ends on a deeper object (eqs. 1-2): no Sobel");
    if (result.hybrid->revealedPixels == 0) {
      const std::string reason = result.hybrid->maskPixels == 0
                                     ? "the ray mask is empty: no ray traced"
                                     : "no mask pixel's composite meets the background: no ray traced";
      result.plan.noteNoWork(passes::RevealPass::kName, reason);
      result.plan.noteNoWork(passes::HybridStage::kGatherBackground, reason);
    }
  }
  result.frameMilliseconds = timings.frameMilliseconds;
  result.memory.peakBytes = context_.memoryPeak();
  result.display = downloadDisplay(display, width, height);
  return result;
}

}  // namespace hmb
