#include "scenes/procedural/scene_builder.h"

#include <cmath>
#include <utility>

#include <glm/gtc/constants.hpp>

namespace hmb::scene::procedural {

Trs makeTrs(const glm::vec3& translation, const glm::quat& rotation, const glm::vec3& scale) {
  Trs trs;
  trs.translation = translation;
  trs.rotation = rotation;
  trs.scale = scale;
  return trs;
}

uint64_t Rng::next() {
  uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

float Rng::uniform(float lo, float hi) {
  const float unit = static_cast<float>(next() >> 40) * (1.0f / 16777216.0f);  // 24 bits
  return lo + (hi - lo) * unit;
}

uint32_t Rng::below(uint32_t n) { return n == 0 ? 0 : static_cast<uint32_t>(next() % n); }

SceneBuilder::SceneBuilder(std::string name) { scene_.name = std::move(name); }

uint32_t SceneBuilder::material(std::string name, const glm::vec3& linearColor, int32_t texture, bool doubleSided) {
  Material m;
  m.name = std::move(name);
  m.baseColorFactor = glm::vec4(linearColor, 1.0f);
  m.baseColorTexture = texture;
  m.doubleSided = doubleSided;
  scene_.materials.push_back(std::move(m));
  return static_cast<uint32_t>(scene_.materials.size() - 1);
}

int32_t SceneBuilder::texture(Texture texture) {
  scene_.textures.push_back(std::move(texture));
  return static_cast<int32_t>(scene_.textures.size() - 1);
}

uint32_t SceneBuilder::mesh(Mesh mesh) {
  scene_.meshes.push_back(std::move(mesh));
  return static_cast<uint32_t>(scene_.meshes.size() - 1);
}

uint32_t SceneBuilder::node(std::string name, const Trs& rest, int32_t parent) {
  Node n;
  n.name = std::move(name);
  n.parent = parent;
  n.local = rest;
  scene_.nodes.push_back(std::move(n));
  return static_cast<uint32_t>(scene_.nodes.size() - 1);
}

uint32_t SceneBuilder::object(std::string name, uint32_t mesh, const Trs& rest, int32_t parent) {
  const uint32_t n = node(std::move(name), rest, parent);
  scene_.instances.push_back(Instance{mesh, n, nextObjectId_++});
  return n;
}

void SceneBuilder::addToObject(uint32_t node, uint32_t mesh) {
  for (const Instance& inst : scene_.instances)
    if (inst.node == node) {
      scene_.instances.push_back(Instance{mesh, node, inst.objectId});
      return;
    }
  scene_.instances.push_back(Instance{mesh, node, nextObjectId_++});
}

void SceneBuilder::keys(uint32_t node, AnimationPath path, Interpolation interpolation, std::vector<float> times,
                        std::vector<glm::vec4> values) {
  AnimationChannel ch;
  ch.node = node;
  ch.path = path;
  ch.interpolation = interpolation;
  ch.times = std::move(times);
  ch.values = std::move(values);
  scene_.channels.push_back(std::move(ch));
}

void SceneBuilder::translationKeys(uint32_t node, const std::vector<float>& times,
                                   const std::vector<glm::vec3>& positions, Interpolation interpolation) {
  std::vector<glm::vec4> values;
  for (const glm::vec3& p : positions) values.emplace_back(p, 0.0f);
  keys(node, AnimationPath::Translation, interpolation, times, std::move(values));
}

void SceneBuilder::spin(uint32_t node, const glm::vec3& axis, float turnsPerSecond, float start, float end) {
  const glm::quat rest = scene_.nodes[node].local.rotation;
  const float quarterTurnSeconds = 0.25f / std::abs(turnsPerSecond);
  const int steps = static_cast<int>(std::ceil((end - start) / quarterTurnSeconds));
  std::vector<float> times;
  std::vector<glm::vec4> values;
  for (int k = 0; k <= steps; ++k) {
    const float t = start + static_cast<float>(k) * quarterTurnSeconds;
    const float angle = glm::two_pi<float>() * turnsPerSecond * (t - start);
    const glm::quat q = glm::angleAxis(angle, glm::normalize(axis)) * rest;
    times.push_back(t);
    values.emplace_back(q.x, q.y, q.z, q.w);
  }
  keys(node, AnimationPath::Rotation, Interpolation::Linear, std::move(times), std::move(values));
}

uint32_t SceneBuilder::camera(const glm::vec3& eye, const glm::vec3& target, float yfov) {
  const uint32_t n = node("camera", makeTrs(eye, lookRotation(target - eye)));
  Camera cam;
  cam.node = static_cast<int32_t>(n);
  cam.yfov = yfov;
  scene_.camera = cam;
  return n;
}

}  // namespace hmb::scene::procedural
