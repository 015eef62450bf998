// Renders one small frame through the installed public API: the umbrella header, a context,
// a scene, the renderer.
#include <cstdio>
#include <exception>

#include <hmblur/hmblur.h>

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
    std::printf("consumer: rendered %ux%u with %zu passes, %u validation errors\n", result.width, result.height,
                result.plan.passes().size(), context.validationErrors());
    return context.validationErrors() == 0 && result.display.pixels.size() == 32u * 18u * 4u ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
