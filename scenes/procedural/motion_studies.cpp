// Motion studies: small scenes made to isolate one kind of screen motion, beside the reference
// scenes (tests/reference/curved_path_test.cpp, bench/results/curved-path/). Each spins one
// checkered object in front of a striped backdrop, a sixth of a turn per exposure.
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/quaternion.hpp>

#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/procedural_scenes.h"
#include "scenes/procedural/scene_builder.h"

namespace hmb::scene::procedural {
namespace {

constexpr float kTurnsPerExposure = 1.0f / 6.0f;

// A backdrop facing the camera at z = -3 behind whatever spins at the origin.
SceneBuilder spinningStage(const std::string& name, const glm::vec3& eye) {
  SceneBuilder b(name);
  const int32_t backdropTexture = b.texture(makeStripeTexture("backdrop", 64, 8, 8, {70, 80, 95}, {150, 140, 120}));
  const uint32_t backdrop = b.material("backdrop", glm::vec3(1.0f), backdropTexture);
  const glm::quat facingCamera = glm::angleAxis(glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f));
  b.object("backdrop", b.mesh(makePlane({16.0f, 16.0f}, backdrop)), makeTrs({0.0f, 0.0f, -3.0f}, facingCamera));
  b.camera(eye, glm::vec3(0.0f), 0.7f);
  b.scene().light.direction = glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f));
  return b;
}

Scene finishSpinning(SceneBuilder& b, uint32_t node, const glm::vec3& axis) {
  Scene& s = b.scene();
  s.settings.fps = 60.0f;
  s.settings.exposure = 1.0f / 60.0f;
  s.settings.frameTime = 0.5f;
  b.spin(node, axis, kTurnsPerExposure / s.settings.exposure, 0.0f, 1.0f);
  return b.finish();
}

}  // namespace

Scene makeSpinningPlate() {
  SceneBuilder b = spinningStage("spinning-plate", {0.0f, 0.0f, 4.0f});
  const int32_t checker = b.texture(makeCheckerTexture("plate", 128, 128, 8, 8, {200, 60, 40}, {240, 230, 200}));
  const uint32_t material = b.material("plate", glm::vec3(1.0f), checker, true);
  const glm::quat facingCamera = glm::angleAxis(glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f));
  const uint32_t plate =
      b.object("plate", b.mesh(makePlane({2.2f, 2.2f}, material)), makeTrs(glm::vec3(0.0f), facingCamera));
  return finishSpinning(b, plate, {0.0f, 0.0f, 1.0f});
}

Scene makeTurntable() {
  SceneBuilder b = spinningStage("turntable", {0.0f, 3.0f, 3.0f});
  const int32_t checker = b.texture(makeCheckerTexture("turntable", 128, 128, 8, 8, {40, 150, 70}, {235, 225, 190}));
  const uint32_t material = b.material("turntable", glm::vec3(1.0f), checker);
  const uint32_t plate = b.object("turntable", b.mesh(makePlane({2.2f, 2.2f}, material)), makeTrs(glm::vec3(0.0f)));
  return finishSpinning(b, plate, {0.0f, 1.0f, 0.0f});
}

Scene makeSpinningBox() {
  SceneBuilder b = spinningStage("spinning-box", {0.0f, 1.0f, 4.0f});
  const int32_t checker = b.texture(makeCheckerTexture("box", 128, 128, 6, 6, {40, 90, 200}, {235, 225, 190}));
  const uint32_t material = b.material("box", glm::vec3(1.0f), checker);
  const uint32_t box = b.object("box", b.mesh(makeBox({0.9f, 0.9f, 0.9f}, material)), makeTrs(glm::vec3(0.0f)));
  return finishSpinning(b, box, {0.0f, 1.0f, 0.0f});
}

}  // namespace hmb::scene::procedural
