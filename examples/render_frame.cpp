// hybrid-mblur as an engine's motion-blur backend, through the library API alone: choose a
// device (hmb::vk::Context), load a scene, render one frame with a method (hmb::Renderer),
// then read the image and what each pass cost. The hmblur CLI is built on the same calls.
//
// Usage: render_frame [--validation] SCENE METHOD OUT.png [WIDTH HEIGHT]
//   SCENE: a reference scene name or a .gltf/.glb file; METHOD: sharp, postprocess, hybrid
//   or reference. With --validation any Khronos validation error makes the exit code 3.
#include <cstdlib>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <hmblur/hmblur.h>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  hmb::vk::ContextOptions deviceOptions;  // deviceIndex -1: the best compute device
  if (!args.empty() && args.front() == "--validation") {
    deviceOptions.validation = true;
    args.erase(args.begin());
  }
  if (args.size() != 3 && args.size() != 5) {
    std::cerr << "usage: render_frame [--validation] SCENE METHOD OUT.png [WIDTH HEIGHT]\n";
    return 2;
  }
  try {
    hmb::vk::Context device(deviceOptions);
    hmb::Renderer renderer(device);
    const hmb::scene::Scene scene = hmb::scene::loadScene(args[0]);

    hmb::RenderSettings settings;  // everything else: the scene's and the method's defaults
    settings.method = hmb::parseMethod(args[1]);
    if (args.size() == 5) {
      settings.width = static_cast<uint32_t>(std::stoul(args[3]));
      settings.height = static_cast<uint32_t>(std::stoul(args[4]));
    }
    const hmb::RenderResult frame = renderer.render(scene, settings);
    const hmb::io::Rgba8Image& image = frame.display;
    if (!stbi_write_png(args[2].c_str(), int(image.width), int(image.height), 4, image.pixels.data(),
                        int(image.width) * 4))
      throw std::runtime_error("cannot write " + args[2]);

    std::cout << hmb::methodName(frame.method) << " " << frame.width << "x" << frame.height << " on " << device.info().name << ": "
              << frame.frameMilliseconds.value_or(0.0) << " ms\n";
    for (const hmb::PlannedPass& pass : frame.plan.passes()) {
      std::cout << "  " << pass.name << ": ";
      if (!pass.run)
        std::cout << "skipped (" << pass.reason << ")\n";
      else if (!pass.within.empty())
        std::cout << "runs inside " << pass.within << "\n";
      else
        std::cout << pass.milliseconds.value_or(0.0) << " ms\n";
    }
    if (frame.hybrid)
      std::cout << "  shutter rays " << frame.hybrid->shutterRayPixels << " px, " << frame.hybrid->shutterRays
                << " rays; ray mask " << frame.hybrid->maskPixels << " px, " << frame.hybrid->revealRays
                << " reveal rays\n";
    if (frame.cutTraces > 0)
      std::cerr << "render_frame: warning: " << frame.cutTraces << " traces cut short by the device's loop limit\n";
    if (deviceOptions.validation && device.validationErrors() > 0) {
      std::cerr << "render_frame: " << device.validationErrors() << " validation errors\n";
      return 3;
    }
  } catch (const std::exception& e) {
    std::cerr << "render_frame: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
