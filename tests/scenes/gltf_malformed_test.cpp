// Malformed files: each must give hmb::Error with one line that starts with the path.
#include <fstream>
#include <limits>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "scenes/gltf_loader.h"
#include "tests/scenes/gltf_writer.h"

namespace hmb::scene {
namespace {

using nlohmann::json;
using test::GltfWriter;

std::filesystem::path dir() { return test::testDataDir("malformed"); }

// Loads `path`, expecting an hmb::Error whose message starts with the path, is one line and
// contains `expected`.
void expectLoadError(const std::filesystem::path& path, const std::string& expected) {
  try {
    (void)loadGltf(path);
    ADD_FAILURE() << path << " loaded, expected an error containing '" << expected << "'";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(path.string(), 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

GltfWriter quadFile() {
  GltfWriter w;
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({test::addQuadPrimitive(w)})}})});
  return w;
}

TEST(GltfMalformedTest, MissingFile) {
  expectLoadError(dir() / "does-not-exist.gltf", "no such file");
  EXPECT_THROW((void)loadScene((dir() / "does-not-exist.GLB").string()), Error);
}

TEST(GltfMalformedTest, NotJson) {
  const auto path = dir() / "garbage.gltf";
  std::ofstream(path) << "this is { not json";
  expectLoadError(path, "");
}

TEST(GltfMalformedTest, TruncatedGlb) {
  const std::vector<uint8_t> glb = quadFile().glbBytes();
  for (size_t keep : {size_t{6}, size_t{20}, glb.size() / 2, glb.size() - 4}) {
    const auto path = dir() / ("truncated-" + std::to_string(keep) + ".glb");
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(keep));
    expectLoadError(path, "");
  }
}

TEST(GltfMalformedTest, IndexOutOfRange) {
  GltfWriter w;
  const int pos = w.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int idx = w.addIndices({0, 1, 7}, test::kUnsignedShort);
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}})}})});
  expectLoadError(w.writeGltf(dir() / "index-range.gltf"), "past the vertex count");
}

TEST(GltfMalformedTest, AccessorPastItsBuffer) {
  GltfWriter w = quadFile();
  w.doc["accessors"][0]["count"] = 400;  // the view holds 4 vertices
  expectLoadError(w.writeGltf(dir() / "accessor-past.gltf"), "past the end");
  GltfWriter v = quadFile();
  v.doc["bufferViews"][0]["byteLength"] = 4096;  // the view claims more than the buffer has
  expectLoadError(v.writeGltf(dir() / "view-past.gltf"), "");
  GltfWriter a = quadFile();
  a.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 99;  // no such accessor
  expectLoadError(a.writeGltf(dir() / "accessor-missing.gltf"), "");
}

TEST(GltfMalformedTest, NanPositionNamesTheAccessor) {
  GltfWriter w;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const int pos = w.addFloats({0, 0, 0, 1, nan, 0, 0, 1, 0}, "VEC3");
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({{{"attributes", {{"POSITION", pos}}}}})}})});
  expectLoadError(w.writeGltf(dir() / "nan.gltf"), "accessor 0");
  GltfWriter inf;
  const int p2 = inf.addFloats({0, 0, 0, 1, 0, 0, 0, std::numeric_limits<float>::infinity(), 0}, "VEC3");
  inf.setSceneRoots({inf.addNode({{"mesh", inf.addMesh({{{"attributes", {{"POSITION", p2}}}}})}})});
  expectLoadError(inf.writeGlb(dir() / "inf.glb"), "non-finite");
}

TEST(GltfMalformedTest, NodeCycles) {
  GltfWriter w;
  const int a = w.addNode({{"children", {1}}});
  w.addNode({{"children", {a}}});
  w.setSceneRoots({a});
  expectLoadError(w.writeGltf(dir() / "cycle.gltf"), "");
  GltfWriter self;
  self.setSceneRoots({self.addNode({{"children", {0}}})});
  expectLoadError(self.writeGltf(dir() / "self-cycle.gltf"), "");
  GltfWriter twoParents;
  const int child = twoParents.addNode(json::object());
  twoParents.setSceneRoots({twoParents.addNode({{"children", {child}}}), twoParents.addNode({{"children", {child}}})});
  expectLoadError(twoParents.writeGltf(dir() / "two-parents.gltf"), "two parents");
}

TEST(GltfMalformedTest, MissingBufferFile) {
  GltfWriter w = quadFile();
  const auto path = w.writeGltf(dir() / "missing-bin.gltf", /*externalBin=*/true);
  std::filesystem::remove(dir() / "missing-bin.bin");
  expectLoadError(path, "");
}

TEST(GltfMalformedTest, MissingImageFile) {
  GltfWriter w;
  json prim = test::addQuadPrimitive(w, 1.0f, true);
  prim["material"] = 0;
  w.doc["images"] = {{{"uri", "no-such-image.png"}}};
  w.doc["textures"] = {{{"source", 0}}};
  w.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  w.setSceneRoots({w.addNode({{"mesh", w.addMesh({prim})}})});
  expectLoadError(w.writeGltf(dir() / "missing-image.gltf"), "image 0");
}

TEST(GltfMalformedTest, DanglingReferences) {
  GltfWriter mesh = quadFile();
  mesh.doc["nodes"][0]["mesh"] = 5;
  expectLoadError(mesh.writeGltf(dir() / "no-mesh.gltf"), "mesh 5");
  GltfWriter material = quadFile();
  material.doc["meshes"][0]["primitives"][0]["material"] = 3;
  expectLoadError(material.writeGltf(dir() / "no-material.gltf"), "material 3");
  GltfWriter root = quadFile();
  root.setSceneRoots({0, 9});
  expectLoadError(root.writeGltf(dir() / "no-root.gltf"), "");
}

TEST(GltfMalformedTest, BadSparseAndAnimationData) {
  GltfWriter sparse = quadFile();
  const std::vector<uint16_t> index = {50};  // past the 4 vertices
  const std::vector<float> value = {0, 0, 0};
  sparse.doc["accessors"][0]["sparse"] = {
      {"count", 1},
      {"indices", {{"bufferView", sparse.addView(index.data(), 2)}, {"componentType", test::kUnsignedShort}}},
      {"values", {{"bufferView", sparse.addView(value.data(), 12)}}}};
  expectLoadError(sparse.writeGltf(dir() / "bad-sparse.gltf"), "sparse");

  GltfWriter anim = quadFile();
  const int times = anim.addFloats({1.0f, 0.5f}, "SCALAR");  // decreasing
  const int values = anim.addFloats({0, 0, 0, 1, 1, 1}, "VEC3");
  anim.doc["animations"] = {{{"samplers", {{{"input", times}, {"output", values}}}},
                             {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
  expectLoadError(anim.writeGltf(dir() / "bad-times.gltf"), "decrease");

  GltfWriter count = quadFile();
  const int t2 = count.addFloats({0.0f, 1.0f, 2.0f}, "SCALAR");
  const int v2 = count.addFloats({0, 0, 0, 1, 1, 1}, "VEC3");  // 2 values for 3 keys
  count.doc["animations"] = {{{"samplers", {{{"input", t2}, {"output", v2}}}},
                              {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
  expectLoadError(count.writeGltf(dir() / "bad-count.gltf"), "keys");
}

}  // namespace
}  // namespace hmb::scene
