#include "runtime/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "runtime/error.h"
#include "runtime/methods/frame_method.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/context.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {
namespace {

io::Rgba8Image downloadDisplay(const vk::Buffer& display, uint32_t width, uint32_t height) {
  const auto packed = display.download<uint32_t>();
  io::Rgba8Image image;
  image.width = width;
  image.height = height;
  image.pixels.resize(size_t(width) * height * 4);
  std::memcpy(image.pixels.data(), packed.data(), image.pixels.size());
  return image;
}

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

void validatePostProcessChoices(const PostProcessChoices& choices) {
  withChoices(passes::PostProcessSettings{}, choices);
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
  if (settings.width == 0 || settings.height == 0)
    throw Error("image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                " is empty; width and height must be at least 1");
  if (settings.width > kMaxImageSide || settings.height > kMaxImageSide)
    throw Error("image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                " exceeds the limit of " + std::to_string(kMaxImageSide) + " pixels per side");
  if (settings.frameTime && !std::isfinite(*settings.frameTime))
    throw Error("frame time must be a finite number of seconds");
  describe(settings.method).validate(settings);
}

std::vector<std::string> methodNames() {
  std::vector<std::string> names;
  for (const MethodDescription& d : methodDescriptions())
    if (d.inDemo) names.emplace_back(d.name);
  return names;
}

struct Renderer::Shared {
  explicit Shared(vk::Context& context)
      : encodeDisplay(context),
        gbuffer(context, passes::defaultVisibilityScheme(context.info())),
        postProcess(context, passes::PostProcessSettings{}),
        recorder(context),
        resources{context, recorder, encodeDisplay, gbuffer, postProcess} {}
  passes::EncodeDisplayPass encodeDisplay;
  passes::GBufferStage gbuffer;
  passes::PostProcessStage postProcess;
  vk::FrameRecorder recorder;
  FrameResources resources;
  std::map<Method, std::unique_ptr<FrameMethod>> methods;
};

Renderer::Renderer(vk::Context& context) : context_(context) {}
Renderer::~Renderer() = default;

FrameMethod& Renderer::methodFor(Method method) {
  std::unique_ptr<FrameMethod>& made = shared_->methods[method];
  if (!made) made = describe(method).make(shared_->resources);
  return *made;
}

RenderResult Renderer::render(const scene::Scene& scene, const RenderSettings& settings) {
  validateRenderSettings(settings);
  if (!shared_) shared_ = std::make_unique<Shared>(context_);
  FrameMethod& method = methodFor(settings.method);

  context_.resetMemoryPeak();
  RenderResult result;
  result.method = settings.method;
  result.settings = settings;
  result.settings.onProgress = nullptr;
  result.width = settings.width;
  result.height = settings.height;
  result.frameTime = settings.frameTime.value_or(scene.settings.frameTime);
  const vk::Buffer display(context_, uint64_t(settings.width) * settings.height * sizeof(uint32_t),
                           vk::MemoryUse::Device, "display (RGBA8)");
  const FrameRequest request{scene, settings, result.frameTime, settings.width, settings.height, display};
  const vk::FrameTimings timings = method.render(request, result);
  result.plan.attachTimings(timings);
  result.frameMilliseconds = timings.frameMilliseconds;
  result.memory.peakBytes = context_.memoryPeak();
  result.display = downloadDisplay(display, settings.width, settings.height);
  return result;
}

}  // namespace hmb
