// Skins and morph targets through the loader: joint influences (two sets, normalized), a
// skinned mesh on an identity root of its own, a skinned mesh instanced twice, morph weights
// from the mesh and the node and their animation in all three interpolations, and the
// generated deforming test scenes (tests/scenes/deforming/). Malformed skins and targets are in
// the malformed corpus (gltf_corpus_test.cpp).
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "scenes/deformation.h"
#include "scenes/gltf_loader.h"
#include "tests/scenes/gltf_writer.h"

namespace hmb::scene {
namespace {

using json = nlohmann::json;
using test::GltfWriter;

std::filesystem::path dir() { return test::testDataDir("deformation"); }

// A quad skinned to two joints with JOINTS_0/1 and WEIGHTS_0/1: vertex 0 on joint 0 alone
// (weights given as 2: normalized to 1; its second influence names joint 77 with no weight,
// which glTF allows), vertex 1 split over both sets, vertex 2 without any weight, vertex 3 on
// joint 1.
GltfWriter skinnedQuad(int instances) {
  GltfWriter w;
  json prim = test::addQuadPrimitive(w);
  const std::vector<uint16_t> joints0 = {0, 77, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};
  const std::vector<uint16_t> joints1 = {0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  prim["attributes"]["JOINTS_0"] = w.addAccessor(w.addView(joints0.data(), 32), test::kUnsignedShort, 4, "VEC4");
  prim["attributes"]["JOINTS_1"] = w.addAccessor(w.addView(joints1.data(), 32), test::kUnsignedShort, 4, "VEC4");
  prim["attributes"]["WEIGHTS_0"] = w.addFloats({2, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  prim["attributes"]["WEIGHTS_1"] = w.addFloats({0, 0, 0, 0, 3, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, "VEC4");
  const int mesh = w.addMesh({prim});
  const int elbow = w.addNode({{"name", "elbow"}, {"translation", {1, 0, 0}}});
  const int shoulder = w.addNode({{"name", "shoulder"}, {"children", {elbow}}});
  w.doc["skins"] = {{{"joints", {shoulder, elbow}}}};
  std::vector<int> roots = {shoulder};
  for (int i = 0; i < instances; ++i)
    roots.push_back(w.addNode({{"mesh", mesh}, {"skin", 0}, {"translation", {0, 0, 5.0 * (i + 1)}}}));
  w.setSceneRoots(roots);
  return w;
}

TEST(GltfDeformationTest, JointInfluencesAreReadNormalizedAndSkinnedMeshesSitOnAnIdentityRoot) {
  const Scene scene = loadGltf(skinnedQuad(1).writeGltf(dir() / "skinned-quad.gltf"));
  ASSERT_EQ(scene.skins.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 1u);
  const Instance& instance = scene.instances[0];
  EXPECT_EQ(instance.skin, 0);
  EXPECT_EQ(instance.morphNode, -1);
  // glTF ignores a skinned mesh's node transform (its translation of 5 in z here).
  EXPECT_EQ(scene.worldMatrixAt(instance.node, 0.0f), glm::mat4(1.0f));
  const Mesh& mesh = scene.meshes[instance.mesh];
  ASSERT_EQ(mesh.influences, 8u);
  EXPECT_EQ(mesh.weights[0], 1.0f);
  EXPECT_EQ(mesh.joints[1], 0u);  // without weight: never read, named 0
  EXPECT_EQ(mesh.weights[8], 0.25f);  // 1 of 1 + 3
  EXPECT_EQ(mesh.weights[12], 0.75f);
  EXPECT_EQ(mesh.joints[12], 1u);
  EXPECT_EQ(mesh.weights[16], 1.0f);  // no weight at all: the first joint's
  ASSERT_EQ(scene.stats.warnings.size(), 1u);
  EXPECT_NE(scene.stats.warnings[0].find("1 vertices without joint weights"), std::string::npos)
      << scene.stats.warnings[0];
  // Joints at their bind pose (no inverse bind matrices: identities) move vertices on joint 1
  // by its translation.
  const DeformedMesh deformed = deformedMeshAt(scene, instance, 0.0f);
  EXPECT_EQ(deformed.positions[0], mesh.positions[0]);
  EXPECT_EQ(deformed.positions[3], mesh.positions[3] + glm::vec3(1, 0, 0));
  EXPECT_NEAR(deformed.positions[1].x, mesh.positions[1].x + 0.75f, 1e-6f);
}

TEST(GltfDeformationTest, ASkinnedMeshInstancedTwiceGetsAMeshPerInstance) {
  const Scene scene = loadGltf(skinnedQuad(2).writeGltf(dir() / "skinned-twice.gltf"));
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_NE(scene.instances[0].mesh, scene.instances[1].mesh);
  EXPECT_EQ(scene.meshes.size(), 2u);
  EXPECT_NE(scene.instances[0].objectId, scene.instances[1].objectId);
  for (const Instance& instance : scene.instances) EXPECT_EQ(instance.skin, 0);
  EXPECT_EQ(scene.meshes[scene.instances[0].mesh].positions, scene.meshes[scene.instances[1].mesh].positions);
}

// A triangle with two morph targets whose node weights are animated by `interpolation`: keys
// at 0 and 1 s, (0, 1) then (1, 0); cubic splines with zero tangents but the first key's
// out-tangent (2, 0) per second.
Scene morphingTriangle(const std::string& interpolation) {
  GltfWriter w;
  const int positions = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int up = w.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int right = w.addFloats({1, 0, 0, 1, 0, 0, 1, 0, 0}, "VEC3");
  json prim = {{"attributes", {{"POSITION", positions}}}, {"targets", {{{"POSITION", up}}, {{"POSITION", right}}}}};
  const int mesh = w.addMesh({prim});
  w.doc["meshes"][mesh]["weights"] = {0.25, 0.5};
  const int node = w.addNode({{"mesh", mesh}});
  w.setSceneRoots({node});
  const int times = w.addFloats({0, 1}, "SCALAR");
  const bool cubic = interpolation == "CUBICSPLINE";
  const int values = cubic ? w.addFloats({0, 0, 0, 1, 2, 0, 0, 0, 1, 0, 0, 0}, "SCALAR")
                           : w.addFloats({0, 1, 1, 0}, "SCALAR");
  w.doc["animations"] = {{{"samplers", {{{"input", times}, {"output", values}, {"interpolation", interpolation}}}},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", node}, {"path", "weights"}}}}}}}};
  return loadGltf(w.writeGltf(dir() / ("morphing-" + interpolation + ".gltf")));
}

TEST(GltfDeformationTest, MorphWeightsFollowTheirChannelInEveryInterpolation) {
  for (const std::string interpolation : {"STEP", "LINEAR", "CUBICSPLINE"}) {
    const Scene scene = morphingTriangle(interpolation);
    ASSERT_EQ(scene.instances.size(), 1u) << interpolation;
    const Instance& instance = scene.instances[0];
    ASSERT_TRUE(instance.deforms()) << interpolation;
    EXPECT_TRUE(scene.stats.warnings.empty()) << interpolation;
    EXPECT_EQ(scene.nodes[instance.node].weights, (std::vector<float>{0.25f, 0.5f})) << "the mesh's, by default";
    EXPECT_EQ(morphWeightsAt(scene, instance, -1.0f), (std::vector<float>{0.0f, 1.0f})) << interpolation;
    EXPECT_EQ(morphWeightsAt(scene, instance, 2.0f), (std::vector<float>{1.0f, 0.0f})) << interpolation;
    const std::vector<float> half = morphWeightsAt(scene, instance, 0.5f);
    if (interpolation == "STEP") EXPECT_EQ(half, (std::vector<float>{0.0f, 1.0f}));
    if (interpolation == "LINEAR") EXPECT_EQ(half, (std::vector<float>{0.5f, 0.5f}));
    if (interpolation == "CUBICSPLINE") {
      // Hermite at u = 1/2: (p0 + p1) / 2 + (m0 - m1) dt / 8, with m0 = (2, 0) per second.
      EXPECT_NEAR(half[0], 0.5f + 2.0f / 8.0f, 1e-6f);
      EXPECT_NEAR(half[1], 0.5f, 1e-6f);
    }
    const DeformedMesh deformed = deformedMeshAt(scene, instance, 0.5f);
    EXPECT_NEAR(deformed.positions[1].z, half[0], 1e-6f) << interpolation;
    EXPECT_NEAR(deformed.positions[1].x, 1.0f + half[1], 1e-6f) << interpolation;
    EXPECT_TRUE(deformationDiffers(scene, instance, 0.25f, 0.75f) || interpolation == "STEP");
    EXPECT_FALSE(deformationDiffers(scene, instance, 1.5f, 2.5f)) << "held past the last key";
  }
}

TEST(GltfDeformationTest, TheGeneratedDeformingScenesLoadWithoutWarnings) {
  const Scene arm = loadGltf(std::filesystem::path(HMB_DEFORMING_SCENES_DIR) / "skinned-arm.gltf");
  EXPECT_TRUE(arm.stats.warnings.empty());
  ASSERT_EQ(arm.skins.size(), 1u);
  EXPECT_EQ(arm.skins[0].joints.size(), 3u);
  EXPECT_EQ(arm.channels.size(), 3u);
  int skinned = 0;
  for (const Instance& instance : arm.instances) skinned += instance.skin >= 0 ? 1 : 0;
  EXPECT_EQ(skinned, 1);
  EXPECT_TRUE(arm.hasDeformation());

  const Scene sphere = loadGltf(std::filesystem::path(HMB_DEFORMING_SCENES_DIR) / "morphing-sphere.gltf");
  EXPECT_TRUE(sphere.stats.warnings.empty());
  ASSERT_EQ(sphere.channels.size(), 1u);
  EXPECT_EQ(sphere.channels[0].path, AnimationPath::Weights);
  int morphing = 0;
  for (const Instance& instance : sphere.instances) {
    if (instance.morphNode < 0) continue;
    ++morphing;
    EXPECT_EQ(sphere.meshes[instance.mesh].targets.size(), 2u);
    EXPECT_TRUE(deformationIsAnimated(sphere, instance));
  }
  EXPECT_EQ(morphing, 1);
}

}  // namespace
}  // namespace hmb::scene
