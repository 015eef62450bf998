// "temple": a colonnade down a long nave (after the paper's SUN TEMPLE shot) with objects
// moving at several depths and speeds: a fast-spinning wheel, a spinning block, an orb
// flying toward the camera, a crate crossing close to the camera and an urn bobbing along a
// curved (cubic spline) path further back.
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/procedural_scenes.h"
#include "scenes/procedural/scene_builder.h"

namespace hmb::scene::procedural {

Scene makeTemple() {
  SceneBuilder b("temple");
  const glm::vec3 xAxis(1.0f, 0.0f, 0.0f), yAxis(0.0f, 1.0f, 0.0f), zAxis(0.0f, 0.0f, 1.0f);

  const int32_t stoneTexture =
      b.texture(makeCheckerTexture("floor slabs", 256, 256, 16, 16, {196, 184, 160}, {150, 136, 112}));
  const uint32_t floorMat = b.material("floor", glm::vec3(1.0f), stoneTexture);
  const uint32_t columnMat = b.material("sandstone", {0.72f, 0.6f, 0.42f});
  const uint32_t wallMat = b.material("wall", {0.55f, 0.45f, 0.35f});
  const uint32_t altarMat = b.material("altar", {0.35f, 0.33f, 0.32f});
  const uint32_t goldMat = b.material("gold", {0.85f, 0.62f, 0.15f});
  const uint32_t spokeMat = b.material("lapis", {0.1f, 0.18f, 0.6f});
  const uint32_t crateMat = b.material("crate", {0.45f, 0.28f, 0.12f});
  const uint32_t urnMat = b.material("urn", {0.1f, 0.45f, 0.35f});
  const uint32_t blockMat = b.material("block", {0.6f, 0.1f, 0.15f});

  // Floor: three 16 m slabs down the nave (z from +8 to -40), 1 m checker cells.
  const uint32_t floorMesh = b.mesh(makePlane({16.0f, 16.0f}, floorMat));
  for (int i = 0; i < 3; ++i)
    b.object("floor " + std::to_string(i), floorMesh, makeTrs({0.0f, 0.0f, -static_cast<float>(i) * 16.0f}));

  // Columns: shaft, base and capital in one mesh, instanced on two rows of eight.
  Mesh column;
  column.name = "column";
  column.material = columnMat;
  appendMesh(column, makeBox({0.6f, 0.15f, 0.6f}, columnMat), glm::translate(glm::mat4(1.0f), {0.0f, 0.15f, 0.0f}));
  appendMesh(column, makeCylinder(0.42f, 5.4f, 32, columnMat, false),
             glm::translate(glm::mat4(1.0f), {0.0f, 0.3f, 0.0f}));
  appendMesh(column, makeBox({0.65f, 0.15f, 0.65f}, columnMat), glm::translate(glm::mat4(1.0f), {0.0f, 5.85f, 0.0f}));
  const uint32_t columnMesh = b.mesh(std::move(column));
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 8; ++i)
      b.object("column " + std::to_string(row * 8 + i), columnMesh,
               makeTrs({row == 0 ? -4.0f : 4.0f, 0.0f, -4.0f - 4.0f * static_cast<float>(i)}));
  const uint32_t lintelMesh = b.mesh(makeBox({0.7f, 0.3f, 16.5f}, columnMat));
  b.object("lintel left", lintelMesh, makeTrs({-4.0f, 6.3f, -18.0f}));
  b.object("lintel right", lintelMesh, makeTrs({4.0f, 6.3f, -18.0f}));
  b.object("back wall", b.mesh(makeBox({8.0f, 4.0f, 0.5f}, wallMat)), makeTrs({0.0f, 4.0f, -36.0f}));
  b.object("altar", b.mesh(makeBox({1.5f, 0.6f, 0.8f}, altarMat)), makeTrs({0.0f, 0.6f, -30.0f}));

  // Sun wheel: gold ring with four blue spokes facing the camera, 4 turns per second
  // (rim at ~30 m/s), in the middle of the nave.
  Mesh wheel = makeTorus(1.2f, 0.09f, 64, 12, goldMat);
  const uint32_t wheelNode = b.object("sun wheel", b.mesh(std::move(wheel)),
                                      makeTrs({0.4f, 3.0f, -9.0f}, glm::angleAxis(glm::half_pi<float>(), xAxis)));
  Mesh spokes;
  spokes.name = "spokes";
  spokes.material = spokeMat;
  for (int k = 0; k < 2; ++k)
    appendMesh(spokes, makeBox({1.15f, 0.05f, 0.08f}, spokeMat),
               glm::rotate(glm::mat4(1.0f), glm::half_pi<float>() * static_cast<float>(k), yAxis));
  appendMesh(spokes, makeCylinder(0.2f, 0.2f, 24, spokeMat), glm::translate(glm::mat4(1.0f), {0.0f, -0.1f, 0.0f}));
  b.addToObject(wheelNode, b.mesh(std::move(spokes)));
  b.spin(wheelNode, zAxis, 4.0f, 0.0f, 2.0f);

  // Block spinning about the vertical on a plinth, 2 turns per second.
  b.object("plinth", b.mesh(makeCylinder(0.5f, 0.8f, 32, altarMat)), makeTrs({-2.5f, 0.0f, -10.0f}));
  const uint32_t block = b.object("spinning block", b.mesh(makeBox({0.35f, 0.35f, 0.35f}, blockMat)),
                                  makeTrs({-2.5f, 1.25f, -10.0f}, glm::angleAxis(0.6f, xAxis)));
  b.spin(block, yAxis, 2.0f, 0.0f, 2.0f);

  // Orb flying down the nave toward the camera at 12 m/s (motion mostly in depth).
  const uint32_t orb = b.object("orb", b.mesh(makeSphere(0.5f, 48, 24, goldMat)), makeTrs({1.5f, 1.6f, -18.0f}));
  b.translationKeys(orb, {0.0f, 2.0f}, {{1.5f, 1.6f, -30.0f}, {1.5f, 1.6f, -6.0f}});

  // Crate crossing close to the camera at 12 m/s.
  const uint32_t crate = b.object("crate", b.mesh(makeBox({0.4f, 0.4f, 0.4f}, crateMat)), makeTrs({0.0f, 0.4f, -1.0f}));
  b.translationKeys(crate, {0.0f, 2.0f}, {{-12.0f, 0.4f, -1.0f}, {12.0f, 0.4f, -1.0f}});

  // Urn drifting left at mid depth on a bobbing cubic-spline path (tangents in m/s).
  const std::vector<glm::vec2> urnProfile = {{0.0f, 0.0f},  {0.18f, 0.0f}, {0.2f, 0.06f}, {0.32f, 0.3f}, {0.3f, 0.5f},
                                             {0.16f, 0.7f}, {0.14f, 0.8f}, {0.2f, 0.86f}, {0.0f, 0.86f}};
  const uint32_t urn = b.object("urn", b.mesh(makeLathe(urnProfile, 40, urnMat)), makeTrs({0.0f, 0.5f, -12.0f}));
  {
    const std::vector<float> times = {0.0f, 1.0f, 2.0f};
    const std::vector<glm::vec3> points = {{10.0f, 0.5f, -12.0f}, {0.0f, 1.3f, -12.0f}, {-10.0f, 0.5f, -12.0f}};
    const std::vector<glm::vec3> slopes = {{-10.0f, 2.0f, 0.0f}, {-10.0f, 0.0f, 0.0f}, {-10.0f, -2.0f, 0.0f}};
    std::vector<glm::vec4> values;
    for (size_t k = 0; k < times.size(); ++k) {
      values.emplace_back(slopes[k], 0.0f);  // in-tangent
      values.emplace_back(points[k], 0.0f);
      values.emplace_back(slopes[k], 0.0f);  // out-tangent
    }
    b.keys(urn, AnimationPath::Translation, Interpolation::CubicSpline, times, std::move(values));
  }

  b.camera({0.8f, 1.7f, 3.0f}, {0.0f, 2.0f, -20.0f}, 0.9f);

  Scene scene = b.finish();
  scene.light.direction = glm::normalize(glm::vec3(0.5f, -1.0f, -0.3f));
  scene.light.color = glm::vec3(1.1f, 1.0f, 0.85f);
  scene.light.ambient = glm::vec3(0.18f, 0.18f, 0.22f);
  scene.settings.softZExtent = 0.03f;  // paper: 3 cm
  scene.settings.edgeThreshold = 0.98f;
  scene.settings.fps = 150.0f;
  scene.settings.exposure = 1.0f / 60.0f;
  scene.settings.frameTime = 1.0f;
  return scene;
}

}  // namespace hmb::scene::procedural
