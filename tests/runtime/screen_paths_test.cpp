// Each pixel's path over the shutter (runtime/metrics/screen_paths.h) on scenes made here, where the
// answer is known in closed form: a plane sliding across the view moves every pixel by the same
// length along a straight line; spinning about the view axis, a pixel r pixels from the axis
// bends r (1 - cos(a / 2)) off the chord of the angle a swept; a camera dollying in bends
// points off the image centre and not at it; and a still frame has no path at all.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/quaternion.hpp>

#include "hmblur/error.h"
#include "runtime/metrics/screen_paths.h"

namespace hmb {
namespace {

constexpr uint32_t kW = 64, kH = 48;
constexpr float kYfov = 0.8f;

// A camera at (0, 0, 5) looking down -Z at a plane object (object id 1) through z = 0; the
// shutter [0.5, 1].
scene::Scene planeScene() {
  scene::Scene s;
  s.nodes.resize(2);
  s.nodes[0].name = "camera";
  s.nodes[0].local.translation = glm::vec3(0.0f, 0.0f, 5.0f);
  s.nodes[1].name = "plane";
  scene::Camera camera;
  camera.node = 0;
  camera.yfov = kYfov;
  camera.znear = 0.1f;
  camera.zfar = 100.0f;
  s.camera = camera;
  scene::Instance instance;
  instance.node = 1;
  instance.objectId = 1;
  s.instances.push_back(instance);
  s.settings.frameTime = 1.0f;
  s.settings.exposure = 0.5f;
  s.settings.fps = 2.0f;
  return s;
}

void animate(scene::Scene& s, uint32_t node, scene::AnimationPath path, glm::vec4 from, glm::vec4 to) {
  scene::AnimationChannel channel;
  channel.node = node;
  channel.path = path;
  channel.times = {0.0f, 1.0f};
  channel.values = {from, to};
  s.channels.push_back(channel);
}

ScreenPaths pathsOf(const scene::Scene& s) {
  const std::vector<float> depth(size_t(kW) * kH, 5.0f);  // the plane fills the view
  const std::vector<uint32_t> ids(size_t(kW) * kH, 1u);
  return screenPaths(s, s.settings.frameTime, kW, kH, depth, ids);
}

// Pixels per world unit at depth 5 (the plane).
float pixelsPerUnit() { return (float(kH) / 2.0f) / (5.0f * std::tan(kYfov / 2.0f)); }

TEST(ScreenPathsTest, ASlideAcrossTheViewIsStraightAndAsLongAsTheSlide) {
  scene::Scene s = planeScene();
  animate(s, 1, scene::AnimationPath::Translation, glm::vec4(0.0f), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  const ScreenPaths p = pathsOf(s);
  EXPECT_FALSE(p.cameraMoves);
  for (const uint32_t i : {0u, kW * kH / 2 + kW / 2, kW * kH - 1}) {
    EXPECT_NEAR(p.length[i], 0.5f * pixelsPerUnit(), 1e-3f) << i;  // half a unit over the shutter
    EXPECT_NEAR(p.bend[i], 0.0f, 1e-3f) << i;
  }
}

TEST(ScreenPathsTest, SpinningAboutTheViewAxisBendsByTheSagittaOfTheArc) {
  scene::Scene s = planeScene();
  // 2 radians a second about z: the shutter's half second sweeps 1 radian.
  const glm::quat spun = glm::angleAxis(2.0f, glm::vec3(0.0f, 0.0f, 1.0f));
  animate(s, 1, scene::AnimationPath::Rotation, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f),
          glm::vec4(spun.x, spun.y, spun.z, spun.w));
  const ScreenPaths p = pathsOf(s);
  // The axis meets the image at its centre, between pixels: a pixel centre's distance from it.
  for (const uint32_t x : {40u, 50u, 60u}) {
    const uint32_t y = kH / 2;
    const float r = std::hypot(float(x) + 0.5f - kW / 2.0f, float(y) + 0.5f - kH / 2.0f);
    const size_t i = size_t(y) * kW + x;
    EXPECT_NEAR(p.bend[i], r * (1.0f - std::cos(0.5f)), 2e-3f * r) << x;
    EXPECT_NEAR(p.length[i], 2.0f * r * std::sin(0.5f), 2e-3f * r) << x;
  }
}

TEST(ScreenPathsTest, ADollyBendsPathsOffTheCentreOnly) {
  scene::Scene s = planeScene();
  animate(s, 0, scene::AnimationPath::Translation, glm::vec4(0.0f, 0.0f, 5.0f, 0.0f),
          glm::vec4(0.0f, 0.0f, 3.0f, 0.0f));
  // The plane at depth 3 at shutter close.
  std::vector<float> depth(size_t(kW) * kH, 3.0f);
  const std::vector<uint32_t> ids(size_t(kW) * kH, 1u);
  const ScreenPaths p = screenPaths(s, 1.0f, kW, kH, depth, ids);
  EXPECT_TRUE(p.cameraMoves);
  const size_t corner = 0, nearCentre = size_t(kH / 2) * kW + kW / 2;
  // The corner pixel's point lies 3 a tan units off the axis on each image axis (a: its
  // position in [-1, 1], tan: the half field of view's), at depth 3; seen from 4, 3.5 and 3 it
  // lands at 3 a (1/4, 1/3.5, 1/3) of the half image, so the mid point lies 3 a (1/3.5 -
  // (1/4 + 1/3) / 2) half images off the chord, and the path is 3 a (1/3 - 1/4) long.
  const glm::vec2 at(2.0f * 0.5f / kW - 1.0f, 2.0f * 0.5f / kH - 1.0f), half(kW / 2.0f, kH / 2.0f);
  const float bendPerS = 3.0f * std::abs(1.0f / 3.5f - (1.0f / 4.0f + 1.0f / 3.0f) / 2.0f);
  EXPECT_NEAR(p.bend[corner], glm::length(bendPerS * at * half), 2e-3f);
  EXPECT_NEAR(p.length[corner], glm::length(3.0f * (1.0f / 3.0f - 1.0f / 4.0f) * at * half), 2e-3f);
  EXPECT_LT(p.bend[nearCentre], 0.05f * p.bend[corner]);
  // Background pixels move only with the camera's rotation: a dolly leaves them still.
  const std::vector<uint32_t> none(size_t(kW) * kH, 0u);
  const ScreenPaths background = screenPaths(s, 1.0f, kW, kH, depth, none);
  EXPECT_NEAR(background.length[corner], 0.0f, 1e-3f);
}

TEST(ScreenPathsTest, AStillFrameHasNoPaths) {
  const scene::Scene s = planeScene();
  const ScreenPaths p = pathsOf(s);
  for (size_t i = 0; i < p.length.size(); ++i) {
    ASSERT_EQ(p.length[i], 0.0f) << i;
    ASSERT_EQ(p.bend[i], 0.0f) << i;
  }
  EXPECT_THROW(screenPaths(s, 1.0f, kW, kH, std::vector<float>(3, 5.0f), std::vector<uint32_t>(size_t(kW) * kH, 1u)),
               Error);
}

}  // namespace
}  // namespace hmb
