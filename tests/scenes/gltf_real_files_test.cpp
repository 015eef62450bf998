// Real glTF 2.0 files from the assimp test models (Debian package assimp-testmodels): they
// load with plausible counts, and the broken ones give hmb::Error. Skipped when the package is
// not installed.
#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "scenes/assimp_test_models.h"
#include "scenes/gltf_loader.h"

namespace hmb::scene {
namespace {

#define REQUIRE_MODELS()                                 \
  const std::filesystem::path root = assimpGltfModels(); \
  if (root.empty()) GTEST_SKIP() << "assimp-testmodels is not installed"

TEST(GltfRealFilesTest, BoxTexturedInAllContainers) {
  REQUIRE_MODELS();
  for (const char* file : {"BoxTextured-glTF/BoxTextured.gltf", "BoxTextured-glTF-Binary/BoxTextured.glb",
                           "BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    SCOPED_TRACE(file);
    const Scene scene = loadGltf(root / file);
    EXPECT_EQ(scene.triangleCount(), 12u);
    ASSERT_EQ(scene.meshes.size(), 1u);
    EXPECT_EQ(scene.meshes[0].positions.size(), 24u);
    EXPECT_EQ(scene.meshes[0].uvs.size(), 24u);
    ASSERT_EQ(scene.textures.size(), 1u);
    EXPECT_GT(scene.textures[0].width, 0u);
    EXPECT_EQ(scene.textures[0].rgba8.size(), size_t{scene.textures[0].width} * scene.textures[0].height * 4);
    ASSERT_EQ(scene.materials.size(), 1u);
    EXPECT_EQ(scene.materials[0].baseColorTexture, 0);
    const Aabb bounds = scene.boundsAt(0.0f);
    EXPECT_NEAR(bounds.extent().x, 1.0f, 1e-4f);
    EXPECT_NEAR(bounds.extent().y, 1.0f, 1e-4f);
  }
}

TEST(GltfRealFilesTest, EngineHasManyParts) {
  REQUIRE_MODELS();
  const Scene scene = loadGltf(root / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  EXPECT_GT(scene.triangleCount(), 50000u);
  EXPECT_GT(scene.nodes.size(), 50u);
  uint32_t maxId = 0;
  for (const Instance& inst : scene.instances) maxId = std::max(maxId, inst.objectId);
  EXPECT_GT(maxId, 20u);
}

TEST(GltfRealFilesTest, CamerasFile) {
  REQUIRE_MODELS();
  const Scene scene = loadGltf(root / "cameras/Cameras.gltf");
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_NEAR(scene.camera->yfov, 0.7f, 1e-6f);
  EXPECT_NEAR(scene.camera->zfar, 100.0f, 1e-4f);
  EXPECT_NEAR(scene.camera->znear, 0.01f, 1e-6f);
  EXPECT_EQ(scene.camera->node, 1);
}

TEST(GltfRealFilesTest, AnimatedFiles) {
  REQUIRE_MODELS();
  const Scene skin = loadGltf(root / "simple_skin/simple_skin.gltf");
  EXPECT_FALSE(skin.channels.empty());
  EXPECT_GT(skin.triangleCount(), 0u);
  EXPECT_TRUE(skin.stats.warnings.empty());
  ASSERT_EQ(skin.skins.size(), 1u);
  EXPECT_EQ(skin.skins[0].joints, (std::vector<uint32_t>{1, 2}));
  ASSERT_EQ(skin.instances.size(), 1u);
  EXPECT_EQ(skin.instances[0].skin, 0);
  EXPECT_TRUE(skin.hasDeformation());
  EXPECT_EQ(skin.meshes[0].influences, 4u);
  const Scene morph = loadGltf(root / "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  EXPECT_EQ(morph.triangleCount(), 12u);
  ASSERT_EQ(morph.channels.size(), 1u);
  EXPECT_EQ(morph.channels[0].path, AnimationPath::Weights);
  EXPECT_EQ(morph.channels[0].weightCount, 2u);
  EXPECT_EQ(morph.meshes[0].targets.size(), 2u);
  EXPECT_TRUE(morph.hasDeformation());
  EXPECT_TRUE(morph.stats.warnings.empty());
}

TEST(GltfRealFilesTest, PrimitiveModes) {
  REQUIRE_MODELS();
  uint32_t triangles = 0, lines = 0, points = 0;
  for (int i = 0; i <= 15; ++i) {
    char name[96];
    std::snprintf(name, sizeof(name), "glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_%02d.gltf", i);
    SCOPED_TRACE(name);
    const Scene scene = loadGltf(root / name);
    triangles += scene.stats.trianglePrimitives;
    lines += scene.stats.linePrimitives;
    points += scene.stats.pointPrimitives;
    if (scene.stats.trianglePrimitives > 0) {
      EXPECT_GT(scene.triangleCount(), 0u);
    }
  }
  EXPECT_GT(triangles, 0u);
  EXPECT_GT(lines, 0u);
  EXPECT_GT(points, 0u);
}

TEST(GltfRealFilesTest, BrokenFilesAreErrors) {
  REQUIRE_MODELS();
  for (const char* file : {"RecursiveNodes/RecursiveNodes.gltf", "IndexOutOfRange/IndexOutOfRange.gltf",
                           "IndexOutOfRange/AllIndicesOutOfRange.gltf", "MissingBin/BoxTextured.gltf",
                           "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb"}) {
    SCOPED_TRACE(file);
    EXPECT_THROW((void)loadGltf(root / file), Error);
  }
}

}  // namespace
}  // namespace hmb::scene
