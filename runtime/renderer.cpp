#include "hmblur/renderer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/hit_shading.h"
#include "hmblur/image.h"
#include "runtime/methods/frame_method.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/post_process_stage.h"
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

// `s` (the scene's) with the user's post-process choices; a tile size not chosen is the filter's,
// scaled with the image. Not validated: the callers validate what they build on it.
passes::PostProcessSettings withChoices(passes::PostProcessSettings s, const RenderSettings& settings) {
  settings::applyAll(passes::postProcessSettingTable(), settings.postprocess, s);
  // A boost chosen one way replaces a default of the other (the hybrid's falls with the speed);
  // both chosen fail validation.
  const passes::PostProcessChoices& chosen = settings.postprocess;
  if (chosen.foregroundBoost && !chosen.foregroundBoostPixels) s.foregroundBoostPixels.reset();
  if (chosen.foregroundBoostPixels && !chosen.foregroundBoost) s.foregroundBoost.reset();
  if (!s.tileSize) {
    // The paper's tile sizes are pixels of a 720-line image; velocities in pixels scale with the
    // image, so the tiles do too (else a small image is a handful of tiles and every blur
    // spills over the whole frame).
    const float linesScale = float(settings.height) / 720.0f;
    s.tileSize = std::max(1u, static_cast<uint32_t>(std::lround(float(passes::describe(s.filter).tileSize) * linesScale)));
  }
  return s;
}

passes::PostProcessSettings validated(passes::PostProcessSettings s) {
  passes::validate(s);
  return s;
}

// One table's settings as a render's: `choices` picks the table's choices out of RenderSettings.
template <class Choices, class Settings>
void addDescriptions(std::vector<RenderSettingDescription>& out, const settings::Table<Choices, Settings>& table,
                     Choices RenderSettings::*choices, const Settings& defaults,
                     const Settings* hybridDefaults = nullptr) {
  for (const auto& setting : table) {
    std::vector<Method> methods;
    for (const MethodDescription& d : methodDescriptions())
      if (settings::readBy(setting.methods, d.name)) methods.push_back(d.method);
    std::string defaultText = setting.defaultText;
    if (hybridDefaults && setting.show(*hybridDefaults) != setting.show(defaults))
      defaultText += "; hybrid " + setting.show(*hybridDefaults);
    std::string help = std::string(setting.help) + " [" + std::string(setting.methods);
    help[0] = char(std::toupper(static_cast<unsigned char>(help[0])));
    if (!setting.accepts.empty()) help += "; " + setting.accepts;
    help += "; default " + defaultText + "]";
    const auto read = [read = setting.read, choices](RenderSettings& r, std::string_view text) { read(r.*choices, text); };
    const auto same = std::find_if(out.begin(), out.end(), [&](const auto& d) { return d.name == setting.name; });
    if (same == out.end()) {
      out.push_back({std::string(setting.name), help, std::string(setting.valueName), setting.flag, methods, read});
    } else {
      for (Method m : methods)
        if (std::find(same->methods.begin(), same->methods.end(), m) == same->methods.end()) same->methods.push_back(m);
      help[0] = char(std::tolower(static_cast<unsigned char>(help[0])));
      same->help += "; " + help;
      same->read = [first = same->read, read](RenderSettings& r, std::string_view text) {
        first(r, text);
        read(r, text);
      };
    }
  }
}

// `s` (the scene's) with the user's hybrid choices and post-process choices for its blur,
// validated, its blur included. Each hybrid method reads its own settings: hybrid-rays traces
// kHybridRaysStrata unless told otherwise, and takes no choice that only the paper's reveal reads.
passes::HybridSettings hybridWithChoices(passes::HybridSettings s, const RenderSettings& settings) {
  const std::string_view method = methodName(settings.method);
  settings::requireChoicesReadBy(passes::postProcessSettingTable(), settings.postprocess, method);
  settings::requireChoicesReadBy(passes::hybridSettingTable(), settings.hybrid, method);
  s.blur = withChoices(s.blur, settings);
  s.shutterRays = settings.method == Method::HybridRays ? passes::kHybridRaysStrata : 0u;
  settings::applyAll(passes::hybridSettingTable(), settings.hybrid, s);
  if (settings.method == Method::HybridRays && s.shutterRays == 0)
    throw Error("hybrid-rays settings: shutter-rays must be 2, 4, 8 or 16 (the paper's method, without them, is "
                "--method hybrid)");
  passes::validate(s);
  return s;
}

}  // namespace

std::vector<RenderSettingDescription> renderSettingDescriptions() {
  std::vector<RenderSettingDescription> out;
  const passes::PostProcessSettings hybridBlur = passes::HybridSettings{}.blur;
  addDescriptions(out, passes::postProcessSettingTable(), &RenderSettings::postprocess, passes::PostProcessSettings{},
                  &hybridBlur);
  addDescriptions(out, passes::hybridSettingTable(), &RenderSettings::hybrid, passes::HybridSettings{});
  addDescriptions(out, passes::referenceSettingTable(), &RenderSettings::reference, passes::ReferenceSettings{});
  return out;
}

// With time slices each gather blurs over one slice of the shutter (Renderer::render).
passes::PostProcessSettings postProcessSettingsFor(const scene::Scene& scene, const RenderSettings& settings) {
  passes::PostProcessSettings s = withChoices(passes::PostProcessSettings::fromScene(scene.settings), settings);
  s.exposure /= float(s.timeSlices);
  return validated(s);
}

passes::HybridSettings hybridSettingsFor(const scene::Scene& scene, const RenderSettings& settings) {
  passes::HybridSettings h = hybridWithChoices(passes::HybridSettings::fromScene(scene.settings), settings);
  h.blur.exposure /= float(h.blur.timeSlices);
  return h;
}

void validatePostProcessChoices(const RenderSettings& settings) {
  validated(withChoices(passes::PostProcessSettings{}, settings));
}

void validateHybridChoices(const RenderSettings& settings) { hybridWithChoices(passes::HybridSettings{}, settings); }

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
  Shared(vk::Context& context, passes::VisibilityScheme visibilityScheme, std::string shadeHit, std::string shadeMiss)
      : hitShading(std::move(shadeHit), std::move(shadeMiss)),
        encodeDisplay(context),
        gbuffer(context, visibilityScheme),
        postProcess(context, passes::PostProcessSettings{}),
        recorder(context),
        resources{context, recorder, encodeDisplay, gbuffer, postProcess, hitShading} {}
  passes::HitShading hitShading;
  passes::EncodeDisplayPass encodeDisplay;
  passes::GBufferStage gbuffer;
  passes::PostProcessStage postProcess;
  vk::FrameRecorder recorder;
  FrameResources resources;
  std::map<Method, std::unique_ptr<FrameMethod>> methods;
};

Renderer::Renderer(vk::Context& context, RendererOptions options) : context_(context), options_(options) {}
Renderer::~Renderer() = default;

FrameMethod& Renderer::methodFor(Method method) {
  std::unique_ptr<FrameMethod>& made = shared_->methods[method];
  if (!made) made = describe(method).make(shared_->resources);
  return *made;
}

RenderResult Renderer::render(const scene::Scene& scene, const RenderSettings& settings) {
  validateRenderSettings(settings);
  const bool blurs = settings.method == Method::PostProcess || settings.method == Method::Hybrid ||
                     settings.method == Method::HybridRays;
  const uint32_t slices = blurs ? settings.postprocess.timeSlices.value_or(1) : 1;
  return slices > 1 ? renderTimeSlices(scene, settings, slices) : renderFrame(scene, settings);
}

// Slice k of K closes at t - (K - 1 - k) E / K: each is the method's frame at that time, its
// gathers blurring over E / K (postProcessSettingsFor), with its own gather seed (base + k) so
// that the slices' jitter does not repeat; the frame is their mean. The slices are K frames on
// the device; their mean is K adds per pixel on the host, where each slice's image already is.
// The G-buffer layers and plan reported are the last slice's (the one closing at the frame
// time); the frame time is the slices' sum.
RenderResult Renderer::renderTimeSlices(const scene::Scene& scene, const RenderSettings& settings, uint32_t slices) {
  const float frameTime = settings.frameTime.value_or(scene.settings.frameTime);
  const float sliceSpan = scene.settings.exposure / float(slices);
  const uint32_t seed = settings.postprocess.seed.value_or(passes::PostProcessSettings{}.seed);
  RenderSettings one = settings;
  std::vector<glm::vec4> sum(size_t(settings.width) * settings.height, glm::vec4(0.0f));
  std::optional<double> milliseconds = 0.0;
  vk::FrameShape shape;
  RenderResult result;
  const auto beautyOf = [](RenderResult& r) -> io::ImageLayer& {
    for (io::ImageLayer& layer : r.image.layers)
      if (layer.name.empty()) return layer;
    throw Error("a time slice's frame has no beauty layer");
  };
  for (uint32_t k = 0; k < slices; ++k) {
    one.frameTime = frameTime - float(slices - 1 - k) * sliceSpan;
    one.postprocess.seed = seed + k;
    result = renderFrame(scene, one);
    const std::vector<float>& beauty = beautyOf(result).values;
    for (size_t i = 0; i < sum.size(); ++i)
      sum[i] += glm::vec4(beauty[4 * i], beauty[4 * i + 1], beauty[4 * i + 2], beauty[4 * i + 3]);
    milliseconds = milliseconds && result.frameMilliseconds ? std::optional(*milliseconds + *result.frameMilliseconds)
                                                             : std::nullopt;
    shape += result.frameShape;
  }
  std::vector<float>& beauty = beautyOf(result).values;
  for (size_t i = 0; i < sum.size(); ++i) {
    sum[i] /= float(slices);
    for (int c = 0; c < 4; ++c) beauty[4 * i + c] = sum[i][c];
  }
  result.display = io::encodeDisplay(settings.width, settings.height, sum);
  // The blur settings reported are the slices': each gather's exposure (E / K), the first
  // slice's seed (slice k uses seed + k).
  if (result.postprocess) result.postprocess->seed = seed;
  if (result.hybrid) result.hybrid->settings.blur.seed = seed;
  result.settings = settings;
  result.settings.onProgress = nullptr;
  result.frameTime = frameTime;
  result.frameMilliseconds = milliseconds;
  result.frameShape = shape;
  return result;
}

RenderResult Renderer::renderFrame(const scene::Scene& scene, const RenderSettings& settings) {
  if (!shared_)
    shared_ = std::make_unique<Shared>(
        context_, options_.visibilityScheme.value_or(passes::defaultVisibilityScheme(context_)),
        options_.shadeHit, options_.shadeMiss);
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
  const vk::FrameRecorder::ShapeMark before = shared_->recorder.mark();
  const vk::FrameTimings timings = method.render(request, result);
  result.frameShape = shared_->recorder.shapeSince(before) - result.setupShape.value_or(vk::FrameShape{});
  result.plan.attachTimings(timings);
  result.frameMilliseconds = timings.frameMilliseconds;
  result.memory.peakBytes = context_.memoryPeak();
  result.display = downloadDisplay(display, settings.width, settings.height);
  return result;
}

}  // namespace hmb
