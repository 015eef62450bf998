// The procedural reference scenes: the properties the renderer and the paper's shots rely on.
#include <cmath>
#include <set>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "scenes/reference_scenes.h"

namespace hmb::scene {
namespace {

uint32_t nodeNamed(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.nodes.size(); ++i)
    if (scene.nodes[i].name == name) return static_cast<uint32_t>(i);
  ADD_FAILURE() << "no node " << name;
  return 0;
}

uint32_t objectIdOf(const Scene& scene, uint32_t node) {
  for (const Instance& inst : scene.instances)
    if (inst.node == node) return inst.objectId;
  ADD_FAILURE() << "node " << node << " has no instance";
  return 0;
}

// Pixel position of a world point at 640x360 seen from the scene camera at time t.
glm::vec2 projectToPixels(const Scene& scene, const glm::vec3& world, float t) {
  const glm::mat4 view = glm::inverse(scene.worldMatrixAt(static_cast<uint32_t>(scene.camera->node), t));
  const glm::vec3 v(view * glm::vec4(world, 1.0f));
  const float tanHalf = std::tan(0.5f * scene.camera->yfov);
  const float depth = -v.z;
  const glm::vec2 ndc(v.x / (depth * tanHalf * 640.0f / 360.0f), v.y / (depth * tanHalf));
  return glm::vec2((ndc.x * 0.5f + 0.5f) * 640.0f, (0.5f - ndc.y * 0.5f) * 360.0f);
}

TEST(ReferenceScenesTest, NamesAndUnknownName) {
  EXPECT_EQ(referenceSceneNames(), (std::vector<std::string>{"living-room", "temple", "bistro"}));
  EXPECT_EQ(motionStudyNames(), (std::vector<std::string>{"spinning-plate", "turntable", "spinning-box"}));
  for (const std::string& name : motionStudyNames()) EXPECT_EQ(makeReferenceScene(name).name, name);
  try {
    (void)makeReferenceScene("pink-room");
    ADD_FAILURE() << "unknown name accepted";
  } catch (const Error& e) {
    const std::string message = e.what();
    for (const std::string& name : referenceSceneNames()) EXPECT_NE(message.find(name), std::string::npos) << message;
    for (const std::string& name : motionStudyNames()) EXPECT_NE(message.find(name), std::string::npos) << message;
  }
}

TEST(ReferenceScenesTest, EveryScenesDataIsConsistent) {
  for (const std::string& name : referenceSceneNames()) {
    SCOPED_TRACE(name);
    const Scene scene = makeReferenceScene(name);
    EXPECT_EQ(scene.name, name);
    ASSERT_TRUE(scene.camera.has_value());
    ASSERT_GE(scene.camera->node, 0);
    EXPECT_GT(scene.settings.softZExtent, 0.0f);
    EXPECT_GE(scene.settings.fps, 100.0f);
    EXPECT_LE(scene.settings.fps, 300.0f);
    EXPECT_NEAR(scene.settings.exposure, 1.0f / 60.0f, 1e-7f);
    EXPECT_NEAR(glm::length(scene.light.direction), 1.0f, 1e-5f);
    for (const Mesh& mesh : scene.meshes) {
      ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
      ASSERT_TRUE(mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size());
      ASSERT_LT(mesh.material, scene.materials.size());
      ASSERT_EQ(mesh.indices.size() % 3, 0u);
      for (uint32_t i : mesh.indices) ASSERT_LT(i, mesh.positions.size());
      for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
    }
    for (const Material& m : scene.materials)
      ASSERT_LT(m.baseColorTexture, static_cast<int32_t>(scene.textures.size()));
    for (const Texture& t : scene.textures) ASSERT_EQ(t.rgba8.size(), size_t{t.width} * t.height * 4);
    for (const Instance& inst : scene.instances) {
      ASSERT_LT(inst.mesh, scene.meshes.size());
      ASSERT_LT(inst.node, scene.nodes.size());
      ASSERT_GE(inst.objectId, 1u);
    }
    for (const AnimationChannel& ch : scene.channels) {
      ASSERT_LT(ch.node, scene.nodes.size());
      for (size_t k = 1; k < ch.times.size(); ++k) ASSERT_LT(ch.times[k - 1], ch.times[k]);
      const size_t perKey = ch.interpolation == Interpolation::CubicSpline ? 3 : 1;
      ASSERT_EQ(ch.values.size(), ch.times.size() * perKey);
      // The shutter of the default frame lies inside the animation.
      EXPECT_LE(ch.times.front(), scene.settings.frameTime - scene.settings.exposure);
      EXPECT_GE(ch.times.back(), scene.settings.frameTime);
    }
    for (const Node& node : scene.nodes) ASSERT_LT(node.parent, static_cast<int32_t>(scene.nodes.size()));
    EXPECT_FALSE(scene.textures.empty());
  }
}

TEST(ReferenceScenesTest, ScenesAreDeterministic) {
  for (const std::string& name : referenceSceneNames()) {
    SCOPED_TRACE(name);
    const Scene a = makeReferenceScene(name);
    const Scene b = makeReferenceScene(name);
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t m = 0; m < a.meshes.size(); ++m) {
      EXPECT_EQ(a.meshes[m].positions, b.meshes[m].positions);
      EXPECT_EQ(a.meshes[m].indices, b.meshes[m].indices);
    }
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (size_t n = 0; n < a.nodes.size(); ++n)
      EXPECT_EQ(a.worldMatrixAt(static_cast<uint32_t>(n), 0.3f), b.worldMatrixAt(static_cast<uint32_t>(n), 0.3f));
    ASSERT_EQ(a.instances.size(), b.instances.size());
    for (size_t i = 0; i < a.instances.size(); ++i) EXPECT_EQ(a.instances[i].objectId, b.instances[i].objectId);
    ASSERT_EQ(a.textures.size(), b.textures.size());
    for (size_t t = 0; t < a.textures.size(); ++t) EXPECT_EQ(a.textures[t].rgba8, b.textures[t].rgba8);
  }
}

TEST(ReferenceScenesTest, LivingRoomVaseMovesFastInFrontOfTheSofa) {
  const Scene scene = makeReferenceScene("living-room");
  const uint32_t vase = nodeNamed(scene, "vase");
  const uint32_t sofa = nodeNamed(scene, "sofa");
  const uint32_t cushion = nodeNamed(scene, "cushion");
  EXPECT_NE(objectIdOf(scene, vase), objectIdOf(scene, sofa));
  EXPECT_NE(objectIdOf(scene, vase), objectIdOf(scene, cushion));
  EXPECT_TRUE(scene.isAnimated(vase));
  EXPECT_FALSE(scene.isAnimated(sofa));
  EXPECT_FALSE(scene.isAnimated(static_cast<uint32_t>(scene.camera->node)));
  EXPECT_NEAR(scene.settings.softZExtent, 0.03f, 1e-6f);
  EXPECT_NEAR(scene.settings.edgeThreshold, 0.90f, 1e-6f);

  // Tens of pixels of blur at 640x360 over the exposure, and the vase is in view.
  const float t = scene.settings.frameTime;
  const glm::vec3 centre(scene.worldMatrixAt(vase, t) * glm::vec4(0.0f, 0.17f, 0.0f, 1.0f));
  const glm::vec3 before(scene.worldMatrixAt(vase, t - scene.settings.exposure) * glm::vec4(0.0f, 0.17f, 0.0f, 1.0f));
  const glm::vec2 now = projectToPixels(scene, centre, t);
  const float blur = glm::length(now - projectToPixels(scene, before, t));
  EXPECT_GT(blur, 20.0f);
  EXPECT_LT(blur, 100.0f);
  EXPECT_GT(now.x, 100.0f);
  EXPECT_LT(now.x, 540.0f);
  EXPECT_GT(now.y, 60.0f);
  EXPECT_LT(now.y, 300.0f);

  // The cushion is behind the vase: farther from the camera.
  const glm::vec3 eye(scene.worldMatrixAt(static_cast<uint32_t>(scene.camera->node), t)[3]);
  const glm::vec3 cushionCentre(scene.worldMatrixAt(cushion, t)[3]);
  EXPECT_GT(glm::length(cushionCentre - eye), glm::length(centre - eye) + 0.5f);
}

TEST(ReferenceScenesTest, TempleHasFastSpinningAndDepthMotion) {
  const Scene scene = makeReferenceScene("temple");
  EXPECT_NEAR(scene.settings.softZExtent, 0.03f, 1e-6f);
  EXPECT_NEAR(scene.settings.edgeThreshold, 0.98f, 1e-6f);
  const float t = scene.settings.frameTime;
  const float e = scene.settings.exposure;
  // Some node turns by more than 10 degrees during the exposure.
  float fastestTurn = 0.0f;
  for (const AnimationChannel& ch : scene.channels) {
    if (ch.path != AnimationPath::Rotation) continue;
    const glm::quat a = scene.localTrsAt(ch.node, t).rotation, b = scene.localTrsAt(ch.node, t - e).rotation;
    fastestTurn = std::max(fastestTurn, glm::angle(glm::normalize(a * glm::inverse(b))));
  }
  EXPECT_GT(fastestTurn, glm::radians(10.0f));
  // The orb moves mostly in depth.
  const uint32_t orb = nodeNamed(scene, "orb");
  const glm::vec3 d = glm::vec3(scene.worldMatrixAt(orb, t)[3]) - glm::vec3(scene.worldMatrixAt(orb, t - e)[3]);
  EXPECT_GT(std::abs(d.z), 2.0f * std::abs(d.x));
  EXPECT_GT(std::abs(d.z), 0.05f);
  // Several moving objects with distinct ids.
  std::set<uint32_t> movingIds;
  for (const Instance& inst : scene.instances)
    if (scene.isAnimated(inst.node)) movingIds.insert(inst.objectId);
  EXPECT_GE(movingIds.size(), 4u);
}

TEST(ReferenceScenesTest, BistroIsDenseWithAMovingCamera) {
  const Scene scene = makeReferenceScene("bistro");
  EXPECT_GE(scene.triangleCount(), 20000u);
  EXPECT_NEAR(scene.settings.softZExtent, 0.005f, 1e-7f);
  EXPECT_NEAR(scene.settings.edgeThreshold, 0.96f, 1e-6f);
  const uint32_t camera = static_cast<uint32_t>(scene.camera->node);
  EXPECT_TRUE(scene.isAnimated(camera));
  const float t = scene.settings.frameTime;
  const glm::vec3 now(scene.worldMatrixAt(camera, t)[3]);
  const glm::vec3 previous(scene.worldMatrixAt(camera, t - 1.0f / scene.settings.fps)[3]);
  EXPECT_GT(glm::length(now - previous), 1e-3f);
  bool movingObject = false;
  for (const Instance& inst : scene.instances)
    if (inst.node != camera && scene.isAnimated(inst.node)) movingObject = true;
  EXPECT_TRUE(movingObject);
  EXPECT_GE(scene.textures.size(), 2u);
}

TEST(ReferenceScenesTest, LoadSceneAppliesDefaultsAndDispatchesOnExtension) {
  const Scene scene = loadScene("temple");
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_GT(scene.camera->znear, 0.0f);
  EXPECT_LT(scene.camera->znear, scene.camera->zfar);
  EXPECT_NEAR(scene.settings.softZExtent, 0.03f, 1e-6f);  // given, kept
  EXPECT_THROW((void)loadScene("no-such-scene"), Error);
  try {
    (void)loadScene("missing/Scene.GLTF");
    ADD_FAILURE() << "missing file loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hmb::scene
