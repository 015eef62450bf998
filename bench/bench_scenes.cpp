#include "bench/bench_scenes.h"

#include <cstdint>
#include <vector>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "scenes/assimp_test_models.h"
#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/scene_builder.h"

namespace hmb::bench {
namespace {

scene::Scene cubeSphere(uint32_t cells) {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  for (int face = 0; face < 6; ++face) {
    const int axis = face / 2;
    const float side = face % 2 ? 1.0f : -1.0f;
    const auto base = static_cast<uint32_t>(positions.size());
    for (uint32_t j = 0; j <= cells; ++j)
      for (uint32_t i = 0; i <= cells; ++i) {
        glm::vec3 p;
        p[axis] = side;
        p[(axis + 1) % 3] = 2.0f * float(i) / float(cells) - 1.0f;
        p[(axis + 2) % 3] = 2.0f * float(j) / float(cells) - 1.0f;
        positions.push_back(glm::normalize(p));
      }
    for (uint32_t j = 0; j < cells; ++j)
      for (uint32_t i = 0; i < cells; ++i) {
        const uint32_t v = base + j * (cells + 1) + i;
        indices.insert(indices.end(), {v, v + 1, v + cells + 2, v, v + cells + 2, v + cells + 1});
      }
  }
  scene::Scene scene = scene::singleMeshScene(positions, indices);
  scene.name = kCubeSphere1m;
  scene::deriveDefaults(scene);  // a camera framing it
  return scene;
}

scene::Scene millionTriangles() {
  using namespace scene::procedural;
  SceneBuilder b(kMillionTriangles);
  const uint32_t grey = b.material("sphere", glm::vec3(0.55f, 0.6f, 0.65f));
  const uint32_t red = b.material("box", glm::vec3(0.8f, 0.15f, 0.1f));
  b.object("sphere", b.mesh(makeSphere(1.0f, 1000, 501, grey)), makeTrs(glm::vec3(0.0f)));  // 1,000,000 triangles
  const uint32_t box = b.object("box", b.mesh(makeBox(glm::vec3(0.2f), red)), makeTrs(glm::vec3(-1.2f, 0.0f, 1.4f)));
  // 2.4 m in 0.5 s: about 30 pixels of blur at 1920x1080 over the 1/60 s exposure.
  b.translationKeys(box, {0.0f, 0.5f}, {{-1.2f, 0.0f, 1.4f}, {1.2f, 0.0f, 1.4f}});
  b.camera({0.0f, 0.3f, 3.5f}, {0.0f, 0.0f, 0.0f}, 0.8f);
  scene::Scene scene = b.finish();
  scene.light.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
  scene.settings.frameTime = 0.25f;
  scene::deriveDefaults(scene);  // near, far and SOFT_Z_EXTENT from the scene
  return scene;
}

}  // namespace

std::optional<std::filesystem::path> cadEnginePath() {
  const std::filesystem::path models = scene::assimpGltfModels();
  const std::filesystem::path path = models / "2CylinderEngine-glTF-Binary" / "2CylinderEngine.glb";
  if (models.empty() || !std::filesystem::exists(path)) return std::nullopt;
  return path;
}

scene::Scene loadBenchScene(const std::string& name) {
  if (name == kCubeSphere1m) return cubeSphere(290);
  if (name == kCadEngine) {
    const std::optional<std::filesystem::path> path = cadEnginePath();
    if (!path) throw Error(std::string(kCadEngine) + ": Debian's assimp-testmodels is not installed");
    scene::Scene scene = scene::loadScene(path->string());
    scene.name = kCadEngine;
    return scene;
  }
  if (name == kMillionTriangles) return millionTriangles();
  return scene::loadScene(name);
}

std::string sceneStem(const std::string& scene) {
  const std::filesystem::path path(scene);
  return path.has_extension() ? path.stem().string() : scene;
}

}  // namespace hmb::bench
