// deriveDefaults: framing, near/far and SOFT_Z_EXTENT follow the scene's own scale.
#include <cmath>

#include <gtest/gtest.h>

#include "hmblur/scene.h"
#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/scene_builder.h"

namespace hmb::scene {
namespace {

using procedural::makeTrs;

// A small room-like arrangement (a floor, a few boxes and a sphere), every length times `unit`.
Scene testScene(float unit) {
  procedural::SceneBuilder b("scaled");
  const uint32_t mat = b.material("m", glm::vec3(0.5f));
  b.object("floor", b.mesh(procedural::makePlane({6.0f * unit, 4.0f * unit}, mat)), makeTrs(glm::vec3(0.0f)));
  const uint32_t box = b.mesh(procedural::makeBox(glm::vec3(0.4f * unit), mat));
  for (int i = 0; i < 4; ++i)
    b.object(
        "box", box,
        makeTrs(glm::vec3(-2.0f + 1.3f * static_cast<float>(i), 0.4f, -1.0f + 0.5f * static_cast<float>(i)) * unit));
  const uint32_t ball = b.object("ball", b.mesh(procedural::makeSphere(0.3f * unit, 32, 16, mat)),
                                 makeTrs(glm::vec3(0.0f, 1.0f, 0.5f) * unit));
  b.translationKeys(ball, {0.0f, 1.0f}, {glm::vec3(-1.0f, 1.0f, 0.5f) * unit, glm::vec3(1.0f, 1.0f, 0.5f) * unit});
  Scene scene = b.finish();
  scene.settings.frameTime = 0.5f;
  return scene;
}

// Gives the scene a camera of its own at `eye`, looking down -z, with near and far left open.
void addCameraAt(Scene& scene, const glm::vec3& eye) {
  Node cameraNode;
  cameraNode.local = makeTrs(eye);
  scene.nodes.push_back(cameraNode);
  Camera camera;
  camera.node = static_cast<int32_t>(scene.nodes.size() - 1);
  scene.camera = camera;
}

glm::mat4 cameraView(const Scene& scene) {
  return glm::inverse(scene.worldMatrixAt(static_cast<uint32_t>(scene.camera->node), scene.settings.frameTime));
}

void expectAllCornersVisible(const Scene& scene, float aspect) {
  const Aabb bounds = scene.boundsAt(scene.settings.frameTime);
  const glm::mat4 view = cameraView(scene);
  const float tanHalf = std::tan(0.5f * scene.camera->yfov);
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? bounds.max.x : bounds.min.x, (i & 2) ? bounds.max.y : bounds.min.y,
                           (i & 4) ? bounds.max.z : bounds.min.z);
    const glm::vec3 v(view * glm::vec4(corner, 1.0f));
    const float depth = -v.z;
    EXPECT_GT(depth, scene.camera->znear) << "corner " << i;
    EXPECT_LT(depth, scene.camera->zfar) << "corner " << i;
    EXPECT_LE(std::abs(v.y / (depth * tanHalf)), 1.0f) << "corner " << i;
    EXPECT_LE(std::abs(v.x / (depth * tanHalf * aspect)), 1.0f) << "corner " << i;
  }
}

TEST(DeriveDefaultsTest, PlacesACameraThatFramesTheScene) {
  Scene scene = testScene(1.0f);
  deriveDefaults(scene);
  ASSERT_TRUE(scene.camera.has_value());
  ASSERT_GE(scene.camera->node, 0);
  EXPECT_GT(scene.camera->znear, 0.0f);
  EXPECT_LT(scene.camera->znear, scene.camera->zfar);
  expectAllCornersVisible(scene, 16.0f / 9.0f);
  expectAllCornersVisible(scene, 1.0f);
  EXPECT_GT(scene.settings.softZExtent, 0.0f);
}

TEST(DeriveDefaultsTest, EverythingScalesWithTheUnit) {
  Scene reference = testScene(1.0f);
  deriveDefaults(reference);
  for (float unit : {1e-3f, 1e3f}) {
    Scene scene = testScene(unit);
    deriveDefaults(scene);
    EXPECT_NEAR(scene.camera->znear / (reference.camera->znear * unit), 1.0f, 1e-3f) << unit;
    EXPECT_NEAR(scene.camera->zfar / (reference.camera->zfar * unit), 1.0f, 1e-3f) << unit;
    EXPECT_NEAR(scene.settings.softZExtent / (reference.settings.softZExtent * unit), 1.0f, 1e-3f) << unit;
    const glm::vec3 eye(scene.worldMatrixAt(static_cast<uint32_t>(scene.camera->node), 0.5f)[3]);
    const glm::vec3 referenceEye(reference.worldMatrixAt(static_cast<uint32_t>(reference.camera->node), 0.5f)[3]);
    EXPECT_NEAR(glm::length(eye - referenceEye * unit) / (glm::length(referenceEye) * unit), 0.0f, 1e-4f);
    expectAllCornersVisible(scene, 16.0f / 9.0f);
  }
}

TEST(DeriveDefaultsTest, SoftZExtentIsAboutTheRoomScaleOfThePaper) {
  Scene scene = testScene(1.0f);  // a 6 m x 4 m room: the paper used 3 cm at that scale
  deriveDefaults(scene);
  EXPECT_GT(scene.settings.softZExtent, 0.005f);
  EXPECT_LT(scene.settings.softZExtent, 0.1f);
}

TEST(DeriveDefaultsTest, GivenCameraGetsNearAndFarFromTheBounds) {
  Scene scene = testScene(1.0f);
  addCameraAt(scene, {0.0f, 1.5f, 8.0f});  // looking down -z at the scene
  deriveDefaults(scene);
  // The nearest geometry is ~5 m away and the farthest ~11 m.
  EXPECT_GT(scene.camera->znear, 0.5f);
  EXPECT_LT(scene.camera->znear, 5.0f);
  EXPECT_GT(scene.camera->zfar, 11.0f);
  EXPECT_LT(scene.camera->zfar, 30.0f);
}

TEST(DeriveDefaultsTest, CameraInsideTheSceneKeepsAPositiveNear) {
  Scene scene = testScene(1.0f);
  addCameraAt(scene, {-2.0f, 0.4f, -1.0f});  // inside the first box
  deriveDefaults(scene);
  EXPECT_GT(scene.camera->znear, 0.0f);
  EXPECT_LT(scene.camera->znear, 0.01f);
  EXPECT_LT(scene.camera->znear, scene.camera->zfar);
  EXPECT_TRUE(std::isfinite(scene.camera->zfar));
}

TEST(DeriveDefaultsTest, KeepsWhatTheSceneGives) {
  Scene scene = testScene(1.0f);
  scene.settings.softZExtent = 0.123f;
  Camera camera;
  camera.node = static_cast<int32_t>(scene.nodes.size());
  camera.znear = 0.5f;
  camera.zfar = 0.0f;  // open: derived, and beyond znear
  scene.nodes.push_back(Node{"cam", -1, makeTrs({0.0f, 1.0f, 10.0f})});
  scene.camera = camera;
  scene.light.direction = {0.0f, -3.0f, 4.0f};
  deriveDefaults(scene);
  EXPECT_EQ(scene.settings.softZExtent, 0.123f);
  EXPECT_EQ(scene.camera->znear, 0.5f);
  EXPECT_GT(scene.camera->zfar, 0.5f);
  EXPECT_NEAR(glm::length(scene.light.direction), 1.0f, 1e-6f);
  EXPECT_NEAR(scene.light.direction.y, -0.6f, 1e-6f);
}

TEST(DeriveDefaultsTest, EmptySceneGetsUsableDefaults) {
  Scene scene;
  scene.light.direction = glm::vec3(0.0f);
  deriveDefaults(scene);
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_GT(scene.camera->znear, 0.0f);
  EXPECT_LT(scene.camera->znear, scene.camera->zfar);
  EXPECT_TRUE(std::isfinite(scene.camera->zfar));
  EXPECT_GT(scene.settings.softZExtent, 0.0f);
  EXPECT_TRUE(std::isfinite(scene.settings.softZExtent));
  EXPECT_NEAR(glm::length(scene.light.direction), 1.0f, 1e-6f);
}

}  // namespace
}  // namespace hmb::scene
