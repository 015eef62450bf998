#include "runtime/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "runtime/error.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/test_pattern_pass.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/context.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {

struct Renderer::Passes {
  explicit Passes(const vk::Context& context) : testPattern(context), encodeDisplay(context), recorder(context) {}
  passes::TestPatternPass testPattern;
  passes::EncodeDisplayPass encodeDisplay;
  vk::FrameRecorder recorder;
};

const std::vector<std::string>& methodNames() {
  static const std::vector<std::string> names = {"test-pattern"};
  return names;
}

void validateRenderSettings(const RenderSettings& settings) {
  const auto& names = methodNames();
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
}

Renderer::Renderer(vk::Context& context) : context_(context) {}
Renderer::~Renderer() = default;

RenderResult Renderer::render(const scene::Scene& scene, const RenderSettings& settings) {
  validateRenderSettings(settings);
  if (!passes_) passes_ = std::make_unique<Passes>(context_);

  RenderResult result;
  result.method = settings.method;
  result.width = settings.width;
  result.height = settings.height;
  result.frameTime = settings.frameTime.value_or(scene.settings.frameTime);

  const uint64_t pixels = uint64_t(settings.width) * settings.height;
  vk::Buffer linear(context_, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "beauty (linear RGBA)");
  vk::Buffer display(context_, pixels * sizeof(uint32_t), vk::MemoryUse::Device, "display (RGBA8)");

  // The test pattern proves the runtime; it does not read the scene.
  result.plan.run(passes::TestPatternPass::kName);
  result.plan.run(passes::EncodeDisplayPass::kName);

  vk::FrameRecorder& frame = passes_->recorder;
  frame.begin();
  passes_->testPattern.record(frame, linear, settings.width, settings.height, result.frameTime);
  passes_->encodeDisplay.record(frame, linear, display, settings.width, settings.height);
  const vk::FrameTimings timings = frame.submitAndWait();
  result.plan.attachTimings(timings);
  result.frameMilliseconds = timings.frameMilliseconds;

  const auto beauty = linear.download<glm::vec4>();
  io::ImageLayer beautyLayer{"", {"R", "G", "B", "A"}, false, {}, {}};
  beautyLayer.values.reserve(beauty.size() * 4);
  for (const glm::vec4& p : beauty) beautyLayer.values.insert(beautyLayer.values.end(), {p.r, p.g, p.b, p.a});
  result.image = {settings.width, settings.height, {std::move(beautyLayer)}};

  const auto packed = display.download<uint32_t>();
  result.display.width = settings.width;
  result.display.height = settings.height;
  result.display.pixels.resize(packed.size() * 4);
  std::memcpy(result.display.pixels.data(), packed.data(), result.display.pixels.size());
  return result;
}

}  // namespace hmb
