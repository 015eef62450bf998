// Loading valid glTF files written by the tests themselves.
#include <algorithm>
#include <cmath>
#include <fstream>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "scenes/gltf_loader.h"
#include "tests/scenes/gltf_writer.h"

namespace hmb::scene {
namespace {

using nlohmann::json;
using test::GltfWriter;

constexpr float kEps = 1e-5f;

void expectVec3(const glm::vec3& actual, const glm::vec3& expected, float eps = kEps) {
  EXPECT_NEAR(actual.x, expected.x, eps);
  EXPECT_NEAR(actual.y, expected.y, eps);
  EXPECT_NEAR(actual.z, expected.z, eps);
}

std::filesystem::path dir() { return test::testDataDir("loader"); }

TEST(GltfLoaderTest, HierarchyMaterialAndTexture) {
  GltfWriter w;
  const json quad = test::addQuadPrimitive(w, 2.0f, /*withUv=*/true);
  json prim = quad;
  prim["material"] = 0;
  const int mesh = w.addMesh({prim});
  // 2x1 RGB texture: red, green.
  const std::vector<uint8_t> png = test::encodePng(2, 1, 3, 8, {255, 0, 0, 0, 255, 0});
  w.doc["images"] = {{{"uri", "data:image/png;base64," + test::base64(png.data(), png.size())}}};
  w.doc["textures"] = {{{"source", 0}}};
  w.doc["materials"] = {
      {{"name", "paint"},
       {"doubleSided", true},
       {"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}}}};
  const int child = w.addNode({{"name", "child"}, {"mesh", mesh}, {"translation", {0, 0, 1}}});
  const int parent =
      w.addNode({{"name", "parent"}, {"children", {child}}, {"translation", {10, 0, 0}}, {"scale", {2, 2, 2}}});
  w.setSceneRoots({parent});
  const Scene scene = loadGltf(w.writeGltf(dir() / "hierarchy.gltf"));

  EXPECT_EQ(scene.name, "hierarchy");
  ASSERT_EQ(scene.nodes.size(), 2u);
  EXPECT_EQ(scene.nodes[0].parent, 1);
  EXPECT_EQ(scene.nodes[1].parent, -1);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_EQ(scene.instances[0].node, 0u);
  EXPECT_EQ(scene.instances[0].objectId, 1u);
  // Child origin: parent scale 2 applied to (0,0,1), then +(10,0,0).
  expectVec3(glm::vec3(scene.worldMatrixAt(0, 0.0f)[3]), {10, 0, 2});

  ASSERT_EQ(scene.meshes.size(), 1u);
  const Mesh& m = scene.meshes[0];
  EXPECT_EQ(m.triangleCount(), 2u);
  ASSERT_EQ(m.uvs.size(), 4u);
  EXPECT_NEAR(m.uvs[2].x, 1.0f, kEps);
  ASSERT_EQ(m.normals.size(), 4u);
  expectVec3(m.normals[0], {0, 0, 1});  // generated: the quad faces +z

  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, "paint");
  EXPECT_TRUE(scene.materials[0].doubleSided);
  EXPECT_NEAR(scene.materials[0].baseColorFactor.y, 0.25f, kEps);
  ASSERT_EQ(scene.materials[0].baseColorTexture, 0);
  ASSERT_EQ(scene.textures.size(), 1u);
  const Texture& t = scene.textures[0];
  EXPECT_EQ(t.width, 2u);
  EXPECT_EQ(t.height, 1u);
  EXPECT_EQ(t.rgba8, (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255}));
}

TEST(GltfLoaderTest, SixteenBitGreyTextureBecomesRgba8) {
  GltfWriter w;
  json prim = test::addQuadPrimitive(w, 1.0f, true);
  prim["material"] = 0;
  const std::vector<uint8_t> png = test::encodePng(2, 1, 1, 16, {65535, 32896});
  w.doc["images"] = {{{"uri", "data:image/png;base64," + test::base64(png.data(), png.size())}}};
  w.doc["textures"] = {{{"source", 0}}};
  w.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({prim})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "grey16.gltf"));
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.textures[0].rgba8, (std::vector<uint8_t>{255, 255, 255, 255, 128, 128, 128, 255}));
}

TEST(GltfLoaderTest, DefaultMaterialWhenPrimitiveHasNone) {
  GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "nomaterial.gltf"));
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.meshes[0].material, 0u);
  EXPECT_EQ(scene.materials[0].baseColorTexture, -1);
  EXPECT_FALSE(scene.materials[0].doubleSided);
}

TEST(GltfLoaderTest, PerspectiveCameraAndIgnoredOrthographic) {
  GltfWriter w;
  w.doc["cameras"] = {
      {{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}},
      {{"type", "perspective"}, {"perspective", {{"yfov", 0.6}, {"aspectRatio", 1.5}, {"znear", 0.05}}}}};
  const int ortho = w.addNode({{"camera", 0}});
  const int persp = w.addNode({{"camera", 1}, {"translation", {0, 1, 5}}});
  w.setSceneRoots({ortho, persp, w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "camera.gltf"));
  ASSERT_TRUE(scene.camera.has_value());
  EXPECT_EQ(scene.camera->node, persp);
  EXPECT_NEAR(scene.camera->yfov, 0.6f, kEps);
  EXPECT_NEAR(scene.camera->aspectRatio, 1.5f, kEps);
  EXPECT_NEAR(scene.camera->znear, 0.05f, kEps);
  EXPECT_EQ(scene.camera->zfar, 0.0f);  // absent: derived later
  EXPECT_FALSE(scene.stats.warnings.empty());
}

TEST(GltfLoaderTest, AnimationChannelsAreSampled) {
  GltfWriter w;
  const int node = w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}, {"translation", {0, 0, 0}}});
  w.setSceneRoots({node});
  const int times = w.addFloats({0.0f, 2.0f}, "SCALAR");
  const int moves = w.addFloats({0, 0, 0, 4, 0, 0}, "VEC3");
  const float s = std::sqrt(0.5f);
  const int turns = w.addFloats({0, 0, 0, 1, 0, s, 0, s}, "VEC4");  // identity, 90 deg about y
  const int steps = w.addFloats({1, 1, 1, 3, 3, 3}, "VEC3");
  const int weights = w.addFloats({0, 1}, "SCALAR");
  w.doc["animations"] = {{{"samplers",
                           {{{"input", times}, {"output", moves}},
                            {{"input", times}, {"output", turns}, {"interpolation", "LINEAR"}},
                            {{"input", times}, {"output", steps}, {"interpolation", "STEP"}},
                            {{"input", times}, {"output", weights}}}},
                          {"channels",
                           {{{"sampler", 0}, {"target", {{"node", node}, {"path", "translation"}}}},
                            {{"sampler", 1}, {"target", {{"node", node}, {"path", "rotation"}}}},
                            {{"sampler", 2}, {"target", {{"node", node}, {"path", "scale"}}}},
                            {{"sampler", 3}, {"target", {{"node", node}, {"path", "weights"}}}}}}}};
  const Scene scene = loadGltf(w.writeGltf(dir() / "animation.gltf"));
  ASSERT_EQ(scene.channels.size(), 3u);  // weights ignored
  EXPECT_FALSE(scene.stats.warnings.empty());
  EXPECT_NEAR(scene.settings.frameTime, 1.0f, kEps);  // middle of the animation
  const Trs mid = scene.localTrsAt(0, 1.0f);
  expectVec3(mid.translation, {2, 0, 0});
  expectVec3(mid.rotation * glm::vec3(1, 0, 0),
             {std::cos(glm::quarter_pi<float>()), 0, -std::sin(glm::quarter_pi<float>())}, 1e-4f);
  expectVec3(mid.scale, {1, 1, 1});
  expectVec3(scene.localTrsAt(0, 2.0f).scale, {3, 3, 3});
  EXPECT_TRUE(scene.isAnimated(0));
}

TEST(GltfLoaderTest, LinesAndPointsAreSkippedAndCounted) {
  GltfWriter w;
  const json tri = test::addQuadPrimitive(w);
  json lines = tri, points = tri, strip = tri;
  lines["mode"] = 1;
  points["mode"] = 0;
  strip["mode"] = 3;  // LINE_STRIP
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({lines, tri, points, strip})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "mixed.gltf"));
  EXPECT_EQ(scene.stats.trianglePrimitives, 1u);
  EXPECT_EQ(scene.stats.linePrimitives, 2u);
  EXPECT_EQ(scene.stats.pointPrimitives, 1u);
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.instances.size(), 1u);
  EXPECT_GE(scene.stats.warnings.size(), 3u);
}

TEST(GltfLoaderTest, StripsAndFansBecomeListsWithConsistentWinding) {
  GltfWriter w;
  // Strip over a 2x2 grid row: 0(0,0) 1(0,1) 2(1,0) 3(1,1) 4(2,0) 5(2,1) -> 4 triangles.
  const int stripPos = w.addFloats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0, 2, 1, 0}, "VEC3");
  json strip = {{"attributes", {{"POSITION", stripPos}}}, {"mode", 5}};
  // Fan around the origin: centre + 4 rim points -> 3 triangles.
  const int fanPos = w.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, -1, 1, 0}, "VEC3");
  json fan = {{"attributes", {{"POSITION", fanPos}}}, {"mode", 6}};
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({strip, fan})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "stripfan.gltf"));
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].triangleCount(), 4u);
  EXPECT_EQ(scene.meshes[1].triangleCount(), 3u);
  for (const Mesh& m : scene.meshes) {
    // Every triangle faces the same way (all -z for the strip order above, all +z for the fan).
    const glm::vec3& p0 = m.positions[m.indices[0]];
    const float first = glm::cross(m.positions[m.indices[1]] - p0, m.positions[m.indices[2]] - p0).z;
    for (size_t t = 0; t < m.indices.size(); t += 3) {
      const glm::vec3& a = m.positions[m.indices[t]];
      const float z = glm::cross(m.positions[m.indices[t + 1]] - a, m.positions[m.indices[t + 2]] - a).z;
      EXPECT_GT(z * first, 0.0f) << m.name << " triangle " << t / 3;
    }
  }
  // The fan's first triangle is (v1, v2, v0) per the glTF spec: counter-clockwise, +z.
  EXPECT_EQ(std::vector<uint32_t>(scene.meshes[1].indices.begin(), scene.meshes[1].indices.begin() + 3),
            (std::vector<uint32_t>{1, 2, 0}));
}

TEST(GltfLoaderTest, NonIndexedByteIndicesAndInterleavedStride) {
  GltfWriter w;
  // Interleaved position + normal, stride 24 bytes; 3 vertices, no indices.
  const std::vector<float> interleaved = {0, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 1, 0, 1, 0, 0, 0, 1};
  const int view = w.addView(interleaved.data(), interleaved.size() * 4, 24);
  const int pos = w.addAccessor(view, test::kFloat, 3, "VEC3", 0);
  const int nrm = w.addAccessor(view, test::kFloat, 3, "VEC3", 12);
  json nonIndexed = {{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}}};
  json byteIndexed = nonIndexed;
  byteIndexed["indices"] = w.addIndices({0, 1, 2, 2, 1, 0}, test::kUnsignedByte);
  // Normalized unsigned-byte uvs.
  const std::vector<uint8_t> uvBytes = {0, 0, 255, 0, 0, 255, 0, 0};
  byteIndexed["attributes"]["TEXCOORD_0"] =
      w.addAccessor(w.addView(uvBytes.data(), uvBytes.size()), test::kUnsignedByte, 3, "VEC2", 0, /*normalized=*/true);
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({nonIndexed, byteIndexed})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "interleaved.gltf"));
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_EQ(scene.meshes[0].indices, (std::vector<uint32_t>{0, 1, 2}));
  expectVec3(scene.meshes[0].positions[2], {0, 1, 0});
  expectVec3(scene.meshes[0].normals[1], {0, 0, 1});
  EXPECT_EQ(scene.meshes[1].triangleCount(), 2u);
  ASSERT_EQ(scene.meshes[1].uvs.size(), 3u);
  EXPECT_NEAR(scene.meshes[1].uvs[1].x, 1.0f, kEps);
  EXPECT_NEAR(scene.meshes[1].uvs[2].y, 1.0f, kEps);
  // Both primitives belong to one node: one object id.
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_EQ(scene.instances[0].objectId, scene.instances[1].objectId);
}

TEST(GltfLoaderTest, SparseAccessorOverridesBaseValues) {
  GltfWriter w;
  const int base = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const std::vector<uint16_t> sparseIndex = {2};
  const std::vector<float> sparseValue = {0, 5, 0};
  const int indexView = w.addView(sparseIndex.data(), 2);
  const int valueView = w.addView(sparseValue.data(), 12);
  w.doc["accessors"][base]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", indexView}, {"componentType", test::kUnsignedShort}}},
      {"values", {{"bufferView", valueView}}}};
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({{{"attributes", {{"POSITION", base}}}}})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "sparse.gltf"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  expectVec3(scene.meshes[0].positions[2], {0, 5, 0});
  expectVec3(scene.meshes[0].positions[1], {1, 0, 0});
}

TEST(GltfLoaderTest, DegenerateTrianglesAreCountedAndDropped) {
  GltfWriter w;
  const int pos = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0}, "VEC3");
  // Valid, repeated index, collinear (zero area).
  const int idx = w.addIndices({0, 1, 2, 0, 0, 1, 0, 1, 3}, test::kUnsignedShort);
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "degenerate.gltf"));
  EXPECT_EQ(scene.stats.degenerateTriangles, 2u);
  EXPECT_EQ(scene.meshes[0].triangleCount(), 1u);
}

TEST(GltfLoaderTest, SharedMeshKeepsOneObjectIdPerNode) {
  GltfWriter w;
  const int mesh = w.addMesh({test::addQuadPrimitive(w), test::addQuadPrimitive(w, 3.0f)});
  const int a = w.addNode({{"mesh", mesh}});
  const int b = w.addNode({{"mesh", mesh}, {"translation", {5, 0, 0}}});
  const int empty = w.addNode({{"children", {a, b}}});
  w.setSceneRoots({empty});
  const Scene scene = loadGltf(w.writeGltf(dir() / "shared.gltf"));
  EXPECT_EQ(scene.meshes.size(), 2u);  // converted once
  ASSERT_EQ(scene.instances.size(), 4u);
  EXPECT_EQ(scene.instances[0].objectId, 1u);
  EXPECT_EQ(scene.instances[1].objectId, 1u);
  EXPECT_EQ(scene.instances[2].objectId, 2u);
  EXPECT_EQ(scene.instances[3].objectId, 2u);
  EXPECT_EQ(scene.triangleCount(), 8u);
}

TEST(GltfLoaderTest, MatrixNodesDecomposeIncludingMirrors) {
  GltfWriter w;
  const int mesh = w.addMesh({test::addQuadPrimitive(w)});
  // Column-major: rotate 90 deg about z, scale 2, translate (1,2,3).
  const int rotated = w.addNode({{"mesh", mesh}, {"matrix", {0, 2, 0, 0, -2, 0, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1}}});
  // Mirror in x.
  const int mirrored = w.addNode({{"mesh", mesh}, {"matrix", {-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}});
  w.setSceneRoots({rotated, mirrored});
  const Scene scene = loadGltf(w.writeGltf(dir() / "matrix.gltf"));
  const glm::mat4 r = scene.worldMatrixAt(static_cast<uint32_t>(rotated), 0.0f);
  expectVec3(glm::vec3(r * glm::vec4(1, 0, 0, 1)), {1, 4, 3});
  expectVec3(glm::vec3(r * glm::vec4(0, 1, 0, 1)), {-1, 2, 3});
  const glm::mat4 m = scene.worldMatrixAt(static_cast<uint32_t>(mirrored), 0.0f);
  expectVec3(glm::vec3(m * glm::vec4(1, 2, 3, 1)), {-1, 2, 3});
  EXPECT_TRUE(scene.stats.warnings.empty());
}

TEST(GltfLoaderTest, DirectionalLightPointsDownTheNodesMinusZ) {
  GltfWriter w;
  w.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  w.doc["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "directional"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 2.0}}};
  const float s = std::sqrt(0.5f);
  // Rotated -90 deg about x: -Z turns into -Y (straight down).
  const int light = w.addNode({{"rotation", {-s, 0, 0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  w.setSceneRoots({light, w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "light.gltf"));
  expectVec3(scene.light.direction, {0, -1, 0}, 1e-5f);
  expectVec3(scene.light.color, {2.0f, 1.0f, 0.5f});
}

TEST(GltfLoaderTest, BinaryGlbLoadsTheSameContent) {
  GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w, 4.0f)})}})});
  const Scene scene = loadGltf(w.writeGlb(dir() / "quad.glb"));
  ASSERT_EQ(scene.meshes.size(), 1u);
  EXPECT_EQ(scene.triangleCount(), 2u);
  expectVec3(scene.meshes[0].positions[2], {4, 4, 0});
  // Upper-case extension and external .bin work too.
  const Scene again = loadGltf(w.writeGltf(dir() / "QUAD_EXTERNAL.GLTF", /*externalBin=*/true));
  EXPECT_EQ(again.triangleCount(), 2u);
}

TEST(GltfLoaderTest, SceneWithoutNodesOrScenes) {
  GltfWriter w;
  const Scene empty = loadGltf(w.writeGltf(dir() / "empty.gltf"));
  EXPECT_TRUE(empty.instances.empty());
  // No "scenes": every root node is used.
  GltfWriter noScenes;
  noScenes.doc.erase("scene");
  noScenes.doc.erase("scenes");
  noScenes.addNode({{"mesh", noScenes.addMesh({test::addQuadPrimitive(noScenes)})}});
  const Scene roots = loadGltf(noScenes.writeGltf(dir() / "noscenes.gltf"));
  EXPECT_EQ(roots.instances.size(), 1u);
}

// The glTF spec (3.12): a file that requires an extension the loader does not implement is
// refused, saying which; Draco's accessors would otherwise fail as an "invalid bufferView".
TEST(GltfLoaderTest, RequiredExtensionsItDoesNotImplementAreRefused) {
  const auto refusal = [](GltfWriter& w, const std::string& name) {
    try {
      loadGltf(w.writeGltf(dir() / name));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  GltfWriter transform;
  transform.setSceneRoots({transform.addNode({{"mesh", transform.addMesh({test::addQuadPrimitive(transform)})}})});
  transform.doc["extensionsUsed"] = {"KHR_texture_transform"};
  transform.doc["extensionsRequired"] = {"KHR_texture_transform"};
  EXPECT_NE(refusal(transform, "requires-transform.gltf").find("requires extension KHR_texture_transform"),
            std::string::npos);

  GltfWriter draco;
  json primitive = test::addQuadPrimitive(draco);
  draco.doc["accessors"][primitive["attributes"]["POSITION"].get<int>()].erase("bufferView");
  primitive["extensions"]["KHR_draco_mesh_compression"] = {{"bufferView", 0}, {"attributes", {{"POSITION", 0}}}};
  draco.setSceneRoots({draco.addNode({{"mesh", draco.addMesh({primitive})}})});
  draco.doc["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  draco.doc["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  EXPECT_NE(refusal(draco, "draco.gltf").find("Draco"), std::string::npos) << refusal(draco, "draco.gltf");

  // What it implements may be required.
  GltfWriter quantized;
  quantized.setSceneRoots({quantized.addNode({{"mesh", quantized.addMesh({test::addQuadPrimitive(quantized)})}})});
  quantized.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
  quantized.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  EXPECT_EQ(refusal(quantized, "quantized.gltf"), "loaded");
}

TEST(GltfLoaderTest, OtherGltfVersionsAreRefusedWithTheReason) {
  const auto refusal = [](const std::filesystem::path& path) {
    try {
      loadGltf(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  w.doc["asset"]["version"] = "1.0";
  EXPECT_NE(refusal(w.writeGltf(dir() / "version1.gltf")).find("a glTF 1.0 file; only glTF 2.0"), std::string::npos);
  w.doc.erase("asset");
  EXPECT_NE(refusal(w.writeGltf(dir() / "no-asset.gltf")).find("no asset version"), std::string::npos);
  // A binary glTF 1.0 container.
  GltfWriter binary;
  binary.setSceneRoots({binary.addNode({{"mesh", binary.addMesh({test::addQuadPrimitive(binary)})}})});
  std::vector<uint8_t> bytes = binary.glbBytes();
  bytes[4] = 1;
  const std::filesystem::path glb = dir() / "version1.glb";
  std::ofstream(glb, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  EXPECT_NE(refusal(glb).find("(glTF 1.0); only glTF 2.0"), std::string::npos) << refusal(glb);
}

// What the shading leaves out is said: extensions used but not implemented, emission, alpha
// modes, and a file with nothing to draw.
TEST(GltfLoaderTest, WhatTheShadingLeavesOutIsAWarning) {
  const auto has = [](const Scene& scene, const std::string& text) {
    return std::any_of(scene.stats.warnings.begin(), scene.stats.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
  };
  GltfWriter w;
  json quad = test::addQuadPrimitive(w);
  quad["material"] = 0;
  w.doc["materials"] = json::array({{{"emissiveFactor", {1.0, 0.5, 0.0}}, {"alphaMode", "BLEND"}},
                                    {{"alphaMode", "MASK"}}});
  w.doc["extensionsUsed"] = {"KHR_materials_clearcoat"};
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({quad})}})});
  const Scene scene = loadGltf(w.writeGltf(dir() / "left-out.gltf"));
  EXPECT_TRUE(has(scene, "extension KHR_materials_clearcoat is not implemented"));
  EXPECT_TRUE(has(scene, "1 material: emission ignored"));
  EXPECT_TRUE(has(scene, "1 material: alphaMode BLEND drawn opaque"));
  EXPECT_TRUE(has(scene, "1 material: alphaMode MASK"));
  EXPECT_FALSE(has(scene, "no triangles"));

  GltfWriter points;
  json point = test::addQuadPrimitive(points);
  point["mode"] = 0;
  points.setSceneRoots({points.addNode({{"mesh", points.addMesh({point})}})});
  const Scene nothing = loadGltf(points.writeGltf(dir() / "points-only.gltf"));
  EXPECT_TRUE(has(nothing, "no triangles to draw"));
}

// A file or folder given as the scene that is not glTF is refused saying what it is; a glTF
// file named otherwise is read by its content.
TEST(LoadSceneTest, WhatIsNotAGltfFileIsRefusedSayingWhatItIs) {
  const auto refusal = [](const std::filesystem::path& path) {
    try {
      loadScene(path.string());
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  };
  const std::filesystem::path png = dir() / "picture.png";
  const std::vector<uint8_t> bytes = test::encodePng(1, 1, 3, 8, {255, 0, 0});
  std::ofstream(png, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  EXPECT_NE(refusal(png).find("a PNG image, not a scene"), std::string::npos) << refusal(png);
  EXPECT_NE(refusal(dir()).find("a directory, not a glTF file"), std::string::npos) << refusal(dir());
  const std::filesystem::path text = dir() / "notes.txt";
  std::ofstream(text) << "not a scene";
  EXPECT_NE(refusal(text).find("not a glTF file"), std::string::npos) << refusal(text);

  GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  const std::filesystem::path renamed = dir() / "quad.bin-scene";
  std::filesystem::copy_file(w.writeGlb(dir() / "quad-for-rename.glb"), renamed,
                             std::filesystem::copy_options::overwrite_existing);
  EXPECT_EQ(loadScene(renamed.string()).triangleCount(), 2u);
}

// The shutter a render asks for replaces the scene's; absurd values are refused.
TEST(LoadSceneTest, ShutterChoiceReplacesTheScenesOwn) {
  GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  const std::string path = w.writeGltf(dir() / "shutter.gltf").string();
  const Scene scene = loadScene(path, ShutterChoice{.fps = 24.0f, .exposureSeconds = 0.01f});
  EXPECT_FLOAT_EQ(scene.settings.fps, 24.0f);
  EXPECT_FLOAT_EQ(scene.settings.exposure, 0.01f);
  const Scene angle = loadScene(path, ShutterChoice{.fps = 60.0f, .shutterAngleDegrees = 180.0f});
  EXPECT_FLOAT_EQ(angle.settings.exposure, 1.0f / 120.0f);
  // Without a choice a glTF file plays at 24 fps under a 180-degree shutter.
  const Scene defaults = loadScene(path);
  EXPECT_FLOAT_EQ(defaults.settings.fps, 24.0f);
  EXPECT_FLOAT_EQ(defaults.settings.exposure, 1.0f / 48.0f);
  EXPECT_FLOAT_EQ(loadScene(path, ShutterChoice{.shutterAngleDegrees = 360.0f}).settings.exposure, 1.0f / 24.0f);
  EXPECT_FLOAT_EQ(loadScene("living-room").settings.fps, 120.0f) << "the reference scenes keep the paper's";
  EXPECT_THROW(loadScene(path, ShutterChoice{.fps = 0.0f}), Error);
  EXPECT_THROW(loadScene(path, ShutterChoice{.exposureSeconds = -1.0f}), Error);
  EXPECT_THROW(loadScene(path, ShutterChoice{.exposureSeconds = std::nanf("")}), Error);
  EXPECT_THROW(loadScene(path, ShutterChoice{.exposureSeconds = 0.01f, .shutterAngleDegrees = 90.0f}), Error);
}

}  // namespace
}  // namespace hmb::scene
