// Renders one small frame through the installed public API: the umbrella header, a context,
// a scene, the renderer; traces it with its own shadeHit and shadeMiss (written against the
// installed GLSL include); then blurs a G-buffer of its own through the engine backend.
#include <cmath>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <hmblur/hmblur.h>

namespace {

std::string textOf(const char* name) {
  std::ifstream in(std::string(CONSUMER_SOURCE_DIR) + "/" + name);
  if (!in) throw std::runtime_error(std::string("cannot read ") + name);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main() {
  try {
    hmb::vk::ContextOptions options;
    options.validation = true;
    hmb::vk::Context context(options);
    hmb::Renderer renderer(context);
    const hmb::scene::Scene scene = hmb::scene::loadScene("temple");
    hmb::RenderSettings settings;
    settings.method = hmb::Method::PostProcess;
    settings.width = 32;
    settings.height = 18;
    const hmb::RenderResult result = renderer.render(scene, settings);

    // The reference traced with the consumer's shading: its sky where every sample missed.
    hmb::RendererOptions shading;
    shading.shadeHit = textOf("shade_hit.glsl");
    shading.shadeMiss = textOf("shade_miss.glsl");
    hmb::Renderer shaded(context, shading);
    settings.method = hmb::Method::Reference;
    settings.reference.samplesPerPixel = 2;
    const hmb::RenderResult reference = shaded.render(scene, settings);
    const std::vector<float>& traced = reference.image.find("")->values;
    size_t sky = 0, outOfRange = 0;
    for (size_t i = 0; i < traced.size(); i += 4) {
      sky += traced[i] == 0.25f && traced[i + 1] == 0.5f && traced[i + 2] == 1.0f;
      for (int c = 0; c < 3; ++c) outOfRange += !(traced[i + c] >= 0.0f && traced[i + c] <= 1.0f);
    }

    // An engine's G-buffer: a bright bar moving 6 pixels a frame to the right over grey.
    constexpr uint32_t kWidth = 32, kHeight = 18, kPixels = kWidth * kHeight;
    std::vector<float> color(4 * kPixels, 0.2f), depth(kPixels, 10.0f), velocity(2 * kPixels, 0.0f);
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 12; x < 16; ++x) {
        const uint32_t i = y * kWidth + x;
        color[4 * i] = color[4 * i + 1] = color[4 * i + 2] = 1.0f;
        depth[i] = 5.0f;
        velocity[2 * i] = 6.0f;
      }
    const hmb::vk::Buffer colorBuffer = hmb::vk::uploadedBuffer(context, color, "colour");
    const hmb::vk::Buffer depthBuffer = hmb::vk::uploadedBuffer(context, depth, "depth");
    const hmb::vk::Buffer velocityBuffer = hmb::vk::uploadedBuffer(context, velocity, "velocity");
    const hmb::vk::Buffer output(context, kPixels * 16, hmb::vk::MemoryUse::Readback, "blurred");
    hmb::EngineBlurSettings blur;
    blur.exposure = 1.0f / 60.0f;
    blur.fps = 60.0f;
    hmb::EngineMotionBlur motionBlur(context, kWidth, kHeight, blur);
    context.submitAndWait([&](VkCommandBuffer commands) {
      motionBlur.record(commands, {colorBuffer.handle(), depthBuffer.handle(), velocityBuffer.handle()},
                        output.handle());
    });
    const std::vector<float> blurred = output.download<float>();
    // Left of the bar, within its blur, the grey is brightened; far from it, it is not.
    const float nearBar = blurred[4 * (9 * kWidth + 10)], farAway = blurred[4 * (9 * kWidth + 2)];
    std::printf("consumer: rendered %ux%u with %zu passes; its own shading: %zu sky pixels, %zu out of range; engine "
                "blur %.3f beside the bar, %.3f away; %u validation errors\n",
                result.width, result.height, result.plan.passes().size(), sky, outOfRange, nearBar, farAway,
                context.validationErrors());
    const bool blurWorked = std::isfinite(nearBar) && nearBar > 0.25f && std::fabs(farAway - 0.2f) < 1e-3f;
    const bool shadingWorked = sky > 0 && outOfRange == 0;
    return context.validationErrors() == 0 && result.display.pixels.size() == 32u * 18u * 4u && blurWorked &&
                   shadingWorked
               ? 0
               : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
