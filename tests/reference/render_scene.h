// One renderer for every test of the reference suite, and the settings those tests vary.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "hmblur/renderer.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {

inline RenderResult renderScene(const scene::Scene& scene, const std::string& method, uint32_t spp, uint32_t seed,
                                std::optional<float> frameTime, uint32_t width, uint32_t height,
                                bool skipUnneededPasses = true) {
  static Renderer renderer(VulkanTest::context());
  RenderSettings settings;
  settings.method = parseMethod(method);
  settings.width = width;
  settings.height = height;
  settings.frameTime = frameTime;
  settings.reference.samplesPerPixel = spp;
  settings.reference.seed = seed;
  settings.skipUnneededPasses = skipUnneededPasses;
  return renderer.render(scene, settings);
}

}  // namespace hmb::test
