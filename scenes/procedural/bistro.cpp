// "bistro": a dense interior (after the paper's BISTRO INTERIOR shot): a bar counter with
// shelves full of bottles, tables with chairs, glasses and plates, pendant lamps. A waiter's
// tray crosses the foreground, a ceiling fan spins, and the camera dollies and pans.
#include <string>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/procedural_scenes.h"
#include "scenes/procedural/scene_builder.h"

namespace hmb::scene::procedural {
namespace {

glm::mat4 at(const glm::vec3& p) { return glm::translate(glm::mat4(1.0f), p); }

std::vector<glm::vec2> wineBottleProfile() {
  return {{0.0f, 0.0f},    {0.036f, 0.0f}, {0.038f, 0.01f},  {0.038f, 0.19f},  {0.034f, 0.215f}, {0.022f, 0.235f},
          {0.014f, 0.26f}, {0.013f, 0.3f}, {0.015f, 0.305f}, {0.015f, 0.315f}, {0.0f, 0.315f}};
}
std::vector<glm::vec2> squatBottleProfile() {
  return {{0.0f, 0.0f},    {0.045f, 0.0f},  {0.048f, 0.012f}, {0.048f, 0.14f}, {0.04f, 0.17f},
          {0.016f, 0.19f}, {0.015f, 0.23f}, {0.018f, 0.235f}, {0.0f, 0.235f}};
}
std::vector<glm::vec2> glassProfile() {  // a wine glass: foot, stem, bowl (open, double-sided)
  return {{0.0f, 0.0f},    {0.035f, 0.0f}, {0.035f, 0.004f}, {0.005f, 0.008f}, {0.004f, 0.07f},
          {0.02f, 0.085f}, {0.04f, 0.11f}, {0.042f, 0.14f},  {0.035f, 0.18f}};
}

Mesh makeChair(uint32_t material) {
  Mesh chair;
  chair.name = "chair";
  chair.material = material;
  appendMesh(chair, makeBox({0.21f, 0.02f, 0.21f}, material), at({0.0f, 0.45f, 0.0f}));
  appendMesh(chair, makeBox({0.21f, 0.2f, 0.02f}, material), at({0.0f, 0.72f, -0.19f}));
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      appendMesh(chair, makeBox({0.018f, 0.225f, 0.018f}, material), at({sx * 0.18f, 0.225f, sz * 0.18f}));
  return chair;
}

Mesh makeRoundTable(uint32_t material) {
  Mesh table;
  table.name = "round table";
  table.material = material;
  appendMesh(table, makeCylinder(0.4f, 0.03f, 48, material), at({0.0f, 0.72f, 0.0f}));
  appendMesh(table, makeCylinder(0.035f, 0.72f, 16, material, false), glm::mat4(1.0f));
  appendMesh(table, makeCylinder(0.22f, 0.02f, 32, material), glm::mat4(1.0f));
  return table;
}

}  // namespace

Scene makeBistro() {
  SceneBuilder b("bistro");
  Rng rng(0x5eed'b157'0000'0001ull);
  const glm::vec3 yAxis(0.0f, 1.0f, 0.0f);

  // Room: 14 m x 10 m, 4 m high; 0.5 m floor tiles, striped wallpaper on the back wall.
  const int32_t tiles = b.texture(makeCheckerTexture("floor tiles", 448, 320, 28, 20, {225, 220, 205}, {40, 40, 45}));
  const int32_t wallpaper = b.texture(makeStripeTexture("wallpaper", 256, 8, 32, {120, 40, 30}, {160, 70, 45}));
  const uint32_t floorMat = b.material("floor", glm::vec3(1.0f), tiles);
  const uint32_t backWallMat = b.material("wallpaper", glm::vec3(1.0f), wallpaper);
  const uint32_t wallMat = b.material("wall", {0.55f, 0.35f, 0.2f});
  const uint32_t ceilingMat = b.material("ceiling", {0.8f, 0.76f, 0.68f});
  const uint32_t counterMat = b.material("counter", {0.3f, 0.14f, 0.06f});
  const uint32_t counterTopMat = b.material("counter top", {0.12f, 0.12f, 0.12f});
  const uint32_t shelfMat = b.material("shelf", {0.4f, 0.24f, 0.12f});
  const uint32_t tableMat = b.material("table", {0.2f, 0.12f, 0.07f});
  const uint32_t chairMat = b.material("chair", {0.5f, 0.3f, 0.1f});
  const uint32_t plateMat = b.material("plate", {0.92f, 0.92f, 0.9f});
  const uint32_t glassMat = b.material("glass", {0.75f, 0.85f, 0.9f}, -1, /*doubleSided=*/true);
  const uint32_t lampMat = b.material("lamp shade", {0.95f, 0.8f, 0.45f}, -1, /*doubleSided=*/true);
  const uint32_t metalMat = b.material("metal", {0.3f, 0.3f, 0.32f});
  const uint32_t trayMat = b.material("tray", {0.7f, 0.7f, 0.72f});
  const uint32_t bottleMats[] = {
      b.material("green bottle", {0.05f, 0.3f, 0.08f}), b.material("amber bottle", {0.45f, 0.2f, 0.03f}),
      b.material("clear bottle", {0.7f, 0.8f, 0.85f}), b.material("blue bottle", {0.08f, 0.15f, 0.5f}),
      b.material("red bottle", {0.5f, 0.05f, 0.07f})};

  b.object("floor", b.mesh(makePlane({14.0f, 10.0f}, floorMat)), makeTrs({0.0f, 0.0f, 0.0f}));
  b.object("ceiling", b.mesh(makePlane({14.0f, 10.0f}, ceilingMat)),
           makeTrs({0.0f, 4.0f, 0.0f}, glm::angleAxis(glm::pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f))));
  b.object("back wall", b.mesh(makePlane({14.0f, 4.0f}, backWallMat)),
           makeTrs({0.0f, 2.0f, -5.0f}, glm::angleAxis(glm::half_pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f))));
  const uint32_t sideWall = b.mesh(makePlane({10.0f, 4.0f}, wallMat));
  for (float side : {-1.0f, 1.0f})
    b.object(
        side < 0 ? "left wall" : "right wall", sideWall,
        makeTrs({side * 7.0f, 2.0f, 0.0f}, glm::angleAxis(side * glm::half_pi<float>(), glm::vec3(0.0f, 0.0f, 1.0f)) *
                                               glm::angleAxis(glm::half_pi<float>(), yAxis)));

  // Bar counter and three shelves of bottles behind it.
  const uint32_t counter =
      b.object("counter", b.mesh(makeBox({4.0f, 0.53f, 0.3f}, counterMat)), makeTrs({-1.0f, 0.53f, -3.6f}));
  b.addToObject(counter, b.mesh([&] {
    Mesh top = makeBox({4.1f, 0.025f, 0.38f}, counterTopMat);
    for (glm::vec3& p : top.positions) p.y += 0.555f;
    return top;
  }()));
  const uint32_t shelfMesh = b.mesh(makeBox({4.0f, 0.02f, 0.15f}, shelfMat));
  std::vector<uint32_t> wine, squat;
  for (uint32_t m : bottleMats) {
    wine.push_back(b.mesh(makeLathe(wineBottleProfile(), 20, m)));
    squat.push_back(b.mesh(makeLathe(squatBottleProfile(), 20, m)));
  }
  for (int shelf = 0; shelf < 3; ++shelf) {
    const float y = 1.4f + 0.5f * static_cast<float>(shelf);
    b.object("shelf " + std::to_string(shelf), shelfMesh, makeTrs({-1.0f, y, -4.83f}));
    for (float x = -4.85f; x < 2.9f; x += rng.uniform(0.1f, 0.16f)) {
      const bool isWine = rng.below(3) != 0;
      const uint32_t mesh = (isWine ? wine : squat)[rng.below(5)];
      b.object("bottle", mesh,
               makeTrs({x, y + 0.02f, -4.83f + rng.uniform(-0.06f, 0.06f)},
                       glm::angleAxis(rng.uniform(0.0f, 6.28f), yAxis)));
    }
  }
  // Bar stools in front of the counter.
  Mesh stool = makeCylinder(0.18f, 0.05f, 24, metalMat);
  for (glm::vec3& p : stool.positions) p.y += 0.75f;
  appendMesh(stool, makeCylinder(0.025f, 0.75f, 12, metalMat, false), glm::mat4(1.0f));
  appendMesh(stool, makeCylinder(0.2f, 0.02f, 24, metalMat), glm::mat4(1.0f));
  const uint32_t stoolMesh = b.mesh(std::move(stool));
  for (int i = 0; i < 7; ++i)
    b.object("stool " + std::to_string(i), stoolMesh, makeTrs({-4.5f + 1.1f * static_cast<float>(i), 0.0f, -2.85f}));

  // Dining tables with chairs and tableware, jittered so that no two look alike.
  const uint32_t tableMesh = b.mesh(makeRoundTable(tableMat));
  const uint32_t chairMesh = b.mesh(makeChair(chairMat));
  const uint32_t plateMesh = b.mesh(makeCylinder(0.11f, 0.012f, 32, plateMat));
  const uint32_t glassMesh = b.mesh(makeLathe(glassProfile(), 24, glassMat));
  const uint32_t candleMesh = b.mesh(makeCylinder(0.02f, 0.12f, 16, plateMat));
  for (int row = 0; row < 2; ++row)
    for (int col = 0; col < 5; ++col) {
      const glm::vec3 center(-5.2f + 2.6f * static_cast<float>(col) + rng.uniform(-0.2f, 0.2f), 0.0f,
                             -0.6f + 2.4f * static_cast<float>(row) + rng.uniform(-0.2f, 0.2f));
      b.object("table", tableMesh, makeTrs(center));
      const float tableTop = 0.75f;
      const int seats = 2 + static_cast<int>(rng.below(3));
      const float phase = rng.uniform(0.0f, 6.28f);
      for (int s = 0; s < seats; ++s) {
        const float angle = phase + glm::two_pi<float>() * static_cast<float>(s) / static_cast<float>(seats);
        const glm::vec3 dir(std::sin(angle), 0.0f, std::cos(angle));
        // The chair's back is on its -z side: turn its +z front toward the table.
        b.object("chair", chairMesh, makeTrs(center + dir * 0.62f, glm::angleAxis(angle + glm::pi<float>(), yAxis)));
        b.object("plate", plateMesh, makeTrs(center + dir * 0.24f + glm::vec3(0.0f, tableTop, 0.0f)));
        const glm::vec3 side(dir.z, 0.0f, -dir.x);
        b.object("glass", glassMesh, makeTrs(center + dir * 0.22f + side * 0.17f + glm::vec3(0.0f, tableTop, 0.0f)));
      }
      b.object("candle", candleMesh, makeTrs(center + glm::vec3(0.0f, tableTop, 0.0f)));
      if (rng.below(2) == 0)
        b.object("bottle", wine[rng.below(5)], makeTrs(center + glm::vec3(0.08f, tableTop, 0.06f)));
    }

  // Pendant lamps over the tables.
  const uint32_t cordMesh = b.mesh(makeCylinder(0.006f, 1.2f, 8, metalMat, false));
  const uint32_t shadeMesh =
      b.mesh(makeLathe({{0.03f, 0.25f}, {0.06f, 0.2f}, {0.16f, 0.06f}, {0.2f, 0.0f}}, 32, lampMat));
  for (int i = 0; i < 5; ++i) {
    const uint32_t lamp =
        b.object("pendant lamp", cordMesh, makeTrs({-5.2f + 2.6f * static_cast<float>(i), 2.8f, 0.6f}));
    b.addToObject(lamp, shadeMesh);
  }

  // Ceiling fan: five blades spinning about the vertical at 3 turns per second.
  Mesh fan = makeCylinder(0.12f, 0.15f, 24, metalMat);
  for (int k = 0; k < 5; ++k) {
    const glm::mat4 blade = glm::rotate(glm::mat4(1.0f), glm::two_pi<float>() * static_cast<float>(k) / 5.0f, yAxis);
    appendMesh(fan, makeBox({0.55f, 0.008f, 0.08f}, metalMat), blade * at({0.65f, 0.05f, 0.0f}));
  }
  const uint32_t fanNode = b.object("ceiling fan", b.mesh(std::move(fan)), makeTrs({0.0f, 3.55f, 0.4f}));
  b.spin(fanNode, yAxis, 3.0f, 0.0f, 2.0f);

  // Waiter's tray with glasses and a bottle crossing the foreground at 6 m/s: one object
  // (a parent node) so that the tray and its load move as one.
  const uint32_t trayNode =
      b.object("tray", b.mesh(makeCylinder(0.22f, 0.015f, 40, trayMat)), makeTrs({0.0f, 1.15f, 2.4f}));
  const uint32_t trayId = b.scene().instances.back().objectId;
  for (int k = 0; k < 3; ++k) {
    const float a = glm::two_pi<float>() * static_cast<float>(k) / 3.0f;
    const uint32_t child = b.node("tray glass", makeTrs({0.12f * std::cos(a), 0.015f, 0.12f * std::sin(a)}),
                                  static_cast<int32_t>(trayNode));
    b.scene().instances.push_back(Instance{glassMesh, child, trayId});
  }
  b.translationKeys(trayNode, {0.0f, 2.0f}, {{-6.0f, 1.15f, 2.4f}, {6.0f, 1.15f, 2.4f}});

  // A chair pushed back in jerks (step keys), still during the default frame's shutter.
  const uint32_t dragged =
      b.object("dragged chair", chairMesh, makeTrs({1.6f, 0.0f, 2.6f}, glm::angleAxis(2.8f, yAxis)));
  b.translationKeys(dragged, {0.25f, 0.75f, 1.25f, 1.75f},
                    {{1.6f, 0.0f, 2.5f}, {1.65f, 0.0f, 2.6f}, {1.7f, 0.0f, 2.7f}, {1.75f, 0.0f, 2.8f}},
                    Interpolation::Step);

  // Camera dollying right at 3 m/s while panning left, at standing eye height.
  const uint32_t cam = b.camera({-3.0f, 1.6f, 4.6f}, {0.0f, 1.5f, -4.0f}, 0.85f);
  b.translationKeys(cam, {0.0f, 2.0f}, {{-3.0f, 1.6f, 4.6f}, {3.0f, 1.6f, 4.3f}});
  {
    const glm::quat from = lookRotation(glm::vec3(0.0f, 1.5f, -4.0f) - glm::vec3(-3.0f, 1.6f, 4.6f));
    const glm::quat to = lookRotation(glm::vec3(-1.0f, 1.5f, -4.0f) - glm::vec3(3.0f, 1.6f, 4.3f));
    b.keys(cam, AnimationPath::Rotation, Interpolation::Linear, {0.0f, 2.0f},
           {{from.x, from.y, from.z, from.w}, {to.x, to.y, to.z, to.w}});
  }

  Scene scene = b.finish();
  scene.light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, -0.4f));
  scene.light.color = glm::vec3(1.0f, 0.92f, 0.8f);
  scene.light.ambient = glm::vec3(0.22f, 0.2f, 0.18f);
  scene.settings.softZExtent = 0.005f;  // paper: 5 mm
  scene.settings.edgeThreshold = 0.96f;
  scene.settings.fps = 240.0f;
  scene.settings.exposure = 1.0f / 60.0f;
  scene.settings.frameTime = 1.0f;
  return scene;
}

}  // namespace hmb::scene::procedural
