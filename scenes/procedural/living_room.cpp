// "living-room": the paper's Figure 5 shot. A red vase slides fast to the right in front of a
// white sofa; the right edge of a pink cushion sits right behind the vase, so the blurred
// vase must reveal the cushion silhouette continuing behind it.
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/procedural_scenes.h"
#include "scenes/procedural/scene_builder.h"

namespace hmb::scene::procedural {

Scene makeLivingRoom() {
  SceneBuilder b("living-room");
  const glm::vec3 xAxis(1.0f, 0.0f, 0.0f), zAxis(0.0f, 0.0f, 1.0f);

  const int32_t woodTexture =
      b.texture(makeCheckerTexture("floor boards", 256, 256, 4, 32, {150, 105, 70}, {120, 82, 52}));
  const int32_t rugTexture = b.texture(makeStripeTexture("rug stripes", 128, 16, 8, {60, 90, 140}, {220, 210, 190}));
  const uint32_t floorMat = b.material("floor", glm::vec3(1.0f), woodTexture);
  const uint32_t rugMat = b.material("rug", glm::vec3(1.0f), rugTexture);
  const uint32_t wallMat = b.material("wall", {0.78f, 0.74f, 0.68f});
  const uint32_t sofaMat = b.material("sofa", {0.88f, 0.88f, 0.86f});
  const uint32_t cushionMat = b.material("cushion", {0.93f, 0.38f, 0.55f});
  const uint32_t vaseMat = b.material("vase", {0.75f, 0.04f, 0.03f}, -1, /*doubleSided=*/true);
  const uint32_t tableMat = b.material("table", {0.28f, 0.17f, 0.09f});
  const uint32_t frameMat = b.material("picture", {0.12f, 0.25f, 0.55f});
  const uint32_t lampMat = b.material("lamp", {0.95f, 0.85f, 0.55f});
  const uint32_t metalMat = b.material("lamp stand", {0.2f, 0.2f, 0.22f});

  // Room: 8 m x 8 m floor, back wall at z = -2.
  b.object("floor", b.mesh(makePlane({8.0f, 8.0f}, floorMat)), makeTrs({0.0f, 0.0f, -1.0f}));
  b.object("rug", b.mesh(makePlane({2.4f, 1.6f}, rugMat)), makeTrs({0.0f, 0.005f, -0.5f}));
  b.object("back wall", b.mesh(makePlane({8.0f, 3.0f}, wallMat)),
           makeTrs({0.0f, 1.5f, -2.0f}, glm::angleAxis(glm::half_pi<float>(), xAxis)));
  b.object("picture", b.mesh(makeBox({0.45f, 0.3f, 0.02f}, frameMat)), makeTrs({1.2f, 1.6f, -1.97f}));

  // Sofa against the wall: base, seat, back and two arms as one object.
  Mesh sofa;
  sofa.material = sofaMat;
  sofa.name = "sofa";
  appendMesh(sofa, makeBox({1.2f, 0.1f, 0.45f}, sofaMat), glm::translate(glm::mat4(1.0f), {0.0f, 0.1f, -1.45f}));
  appendMesh(sofa, makeBox({1.0f, 0.125f, 0.42f}, sofaMat), glm::translate(glm::mat4(1.0f), {0.0f, 0.325f, -1.43f}));
  appendMesh(sofa, makeBox({1.0f, 0.36f, 0.12f}, sofaMat), glm::translate(glm::mat4(1.0f), {0.0f, 0.56f, -1.78f}));
  for (float side : {-1.0f, 1.0f})
    appendMesh(sofa, makeBox({0.12f, 0.26f, 0.45f}, sofaMat),
               glm::translate(glm::mat4(1.0f), {side * 1.1f, 0.46f, -1.45f}));
  b.object("sofa", b.mesh(std::move(sofa)), makeTrs(glm::vec3(0.0f)));

  // Cushion leaning on the back, rolled so that its right edge runs diagonally.
  const glm::quat cushionTilt = glm::angleAxis(0.3f, zAxis) * glm::angleAxis(-0.25f, xAxis);
  b.object("cushion", b.mesh(makeBox({0.27f, 0.24f, 0.07f}, cushionMat)), makeTrs({-0.42f, 0.7f, -1.6f}, cushionTilt));

  // Coffee table: top and four legs.
  Mesh table;
  table.material = tableMat;
  table.name = "coffee table";
  appendMesh(table, makeBox({0.6f, 0.025f, 0.3f}, tableMat), glm::translate(glm::mat4(1.0f), {0.0f, 0.4f, 0.0f}));
  for (float sx : {-1.0f, 1.0f})
    for (float sz : {-1.0f, 1.0f})
      appendMesh(table, makeBox({0.025f, 0.19f, 0.025f}, tableMat),
                 glm::translate(glm::mat4(1.0f), {sx * 0.55f, 0.19f, sz * 0.25f}));
  b.object("coffee table", b.mesh(std::move(table)), makeTrs({0.0f, 0.0f, -0.45f}));

  // Floor lamp on the right.
  const uint32_t lamp =
      b.object("lamp", b.mesh(makeCylinder(0.015f, 1.5f, 12, metalMat)), makeTrs({1.6f, 0.0f, -1.6f}));
  b.addToObject(lamp, b.mesh(makeLathe({{0.0f, 1.45f}, {0.22f, 1.45f}, {0.14f, 1.75f}, {0.0f, 1.75f}}, 32, lampMat)));

  // The vase: a revolved profile, open at the top (double-sided), sliding along +x at 9 m/s.
  const std::vector<glm::vec2> vaseProfile = {{0.0f, 0.0f},    {0.05f, 0.0f},    {0.066f, 0.03f}, {0.084f, 0.09f},
                                              {0.09f, 0.14f},  {0.082f, 0.2f},   {0.06f, 0.255f}, {0.042f, 0.29f},
                                              {0.04f, 0.32f},  {0.048f, 0.345f}, {0.052f, 0.35f}, {0.045f, 0.35f},
                                              {0.036f, 0.32f}, {0.034f, 0.29f}};
  const float tableTop = 0.425f;
  const uint32_t vase =
      b.object("vase", b.mesh(makeLathe(vaseProfile, 48, vaseMat)), makeTrs({0.0f, tableTop, -0.45f}));
  b.translationKeys(vase, {0.0f, 0.2f, 0.4f},
                    {{-1.8f, tableTop, -0.45f}, {0.0f, tableTop, -0.45f}, {1.8f, tableTop, -0.45f}});

  // Camera at seated eye height, looking at the vase with the cushion's edge behind it.
  // From 1.8 m with a 0.7 rad field of view, 360 rows span 1.3 m: 9 m/s over 1/60 s is ~40 px.
  b.camera({0.3f, 0.75f, 1.3f}, {0.0f, 0.6f, -0.45f}, 0.7f);

  Scene scene = b.finish();
  scene.light.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.5f));
  scene.light.color = glm::vec3(1.0f);
  scene.light.ambient = glm::vec3(0.2f);
  scene.settings.softZExtent = 0.03f;  // paper: 3 cm
  scene.settings.edgeThreshold = 0.90f;
  scene.settings.fps = 120.0f;
  scene.settings.exposure = 1.0f / 60.0f;
  scene.settings.frameTime = 0.2f;
  return scene;
}

}  // namespace hmb::scene::procedural
