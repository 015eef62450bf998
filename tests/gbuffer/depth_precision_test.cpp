// Depth precision at extreme near/far ratios: with near 1e-3 and far 1e6, two tilted plates
// 0.05 apart between 630 and 2400 units away (a part in 1e4 to 5e4 of their distance) and a
// box 1e-2 from the eye. The rasterized frame must show what the ray-traced reference shows.
// With the standard depth mapping (z/w = 1 - n/d near the far end) float depth steps there are
// tens of units long and the back plate shows through the front one; reversed depth keeps
// them apart (kernels/raster/raster_layout.h).
#include <cstdlib>
#include <iostream>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "hmblur/renderer.h"
#include "hmblur/scene.h"
#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/scene_builder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

namespace proc = scene::procedural;

constexpr uint32_t kWidth = 160, kHeight = 90;

scene::Scene nearCoincidentPlates() {
  proc::SceneBuilder b("near-coincident plates far away");
  // makePlane's normal is +y; tilted 40 degrees from it towards the camera, the plates run
  // away from the eye like a floor seen from above.
  const glm::quat tilt = glm::angleAxis(glm::radians(40.0f), glm::vec3(1, 0, 0));
  const glm::vec3 normal = tilt * glm::vec3(0, 1, 0);
  const glm::vec3 centre(0.0f, 0.0f, -1000.0f);
  b.object("back plate", b.mesh(proc::makePlane(glm::vec2(8000.0f), b.material("grey", glm::vec3(0.5f)))),
           proc::makeTrs(centre, tilt));
  b.object("front plate", b.mesh(proc::makePlane(glm::vec2(8000.0f), b.material("red", glm::vec3(0.8f, 0.2f, 0.1f)))),
           proc::makeTrs(centre + 0.05f * normal, tilt));
  b.object("near box", b.mesh(proc::makeBox(glm::vec3(1e-3f), b.material("blue", glm::vec3(0.2f, 0.3f, 0.9f)))),
           proc::makeTrs(glm::vec3(3e-3f, -1e-3f, -1e-2f)));
  b.camera(glm::vec3(0.0f), glm::vec3(0, 0, -1), 0.9f);
  b.scene().camera->znear = 1e-3f;
  b.scene().camera->zfar = 1e6f;
  b.scene().light.direction = glm::normalize(glm::vec3(0.3f, -0.5f, -1.0f));
  scene::Scene scene = b.finish();
  scene::deriveDefaults(scene);
  return scene;
}

class DepthPrecisionTest : public VulkanTest {};

TEST_F(DepthPrecisionTest, SurfacesAPartIn1e4ApartWithNear1eMinus3AndFar1e6RasterAsTheReferenceSeesThem) {
  const scene::Scene scene = nearCoincidentPlates();
  ASSERT_EQ(scene.camera->znear, 1e-3f) << "the scene's own planes are kept";
  ASSERT_EQ(scene.camera->zfar, 1e6f);
  Renderer renderer(context());
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.method = Method::Sharp;
  const RenderResult sharp = renderer.render(scene, settings);
  settings.method = Method::Reference;
  settings.reference.samplesPerPixel = 16;
  const RenderResult reference = renderer.render(scene, settings);
  ASSERT_EQ(sharp.display.pixels.size(), size_t(kWidth) * kHeight * 4);
  ASSERT_EQ(reference.display.pixels.size(), sharp.display.pixels.size());

  // Display values (0-255) more than 2 apart in any channel; the box's silhouette may differ on
  // a pixel or two where the rasterizer's snapped edges and the ray test part ways.
  size_t differing = 0, red = 0;
  for (size_t i = 0; i < size_t(kWidth) * kHeight; ++i) {
    bool differs = false;
    for (size_t c = 0; c < 3; ++c)
      differs |= std::abs(int(sharp.display.pixels[i * 4 + c]) - int(reference.display.pixels[i * 4 + c])) > 2;
    differing += differs ? 1 : 0;
    red += sharp.display.pixels[i * 4] > sharp.display.pixels[i * 4 + 1] + 64 ? 1 : 0;
  }
  RecordProperty("pixels_differing", std::to_string(differing));
  std::cout << "[ depth     ] sharp vs reference: " << differing << " of " << kWidth * kHeight
            << " pixels differ by more than 2/255; front plate on " << red << "\n";
  EXPECT_LT(differing, 20u) << "pixels where the sharp frame and the 16-spp reference differ by more than 2/255";
  EXPECT_GT(red, size_t(kWidth) * kHeight / 2) << "the front plate fills most of the frame";
}

}  // namespace
}  // namespace hmb::test
