#include "scenes/deformation.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace hmb::scene {
namespace {

// A weights channel at t: weightCount values, interpolated as glTF says (cubic splines with
// tangents per second, as for transforms). False when the channel is malformed.
bool sampleWeights(const AnimationChannel& ch, float t, std::vector<float>& out) {
  const size_t keys = ch.times.size(), n = ch.weightCount;
  const bool cubic = ch.interpolation == Interpolation::CubicSpline;
  const size_t stride = cubic ? 3 : 1;
  if (keys == 0 || n == 0 || ch.weights.size() < keys * stride * n) return false;
  const auto at = [&](size_t key, size_t element, size_t w) { return ch.weights[(key * stride + element) * n + w]; };
  const size_t value = cubic ? 1 : 0;
  const KeySegment s = keySegment(ch.times, t);
  out.resize(n);
  for (size_t w = 0; w < n; ++w) {
    if (s.k0 == s.k1 || ch.interpolation == Interpolation::Step) {
      out[w] = at(s.k0, value, w);
    } else if (ch.interpolation == Interpolation::Linear) {
      out[w] = at(s.k0, 0, w) + s.u * (at(s.k1, 0, w) - at(s.k0, 0, w));
    } else {
      out[w] = cubicSpline(at(s.k0, 1, w), at(s.k0, 2, w), at(s.k1, 1, w), at(s.k1, 0, w), s.u, s.dt);
    }
  }
  return true;
}

}  // namespace

std::vector<float> morphWeightsAt(const Scene& scene, const Instance& instance, float t) {
  if (instance.morphNode < 0 || instance.mesh >= scene.meshes.size()) return {};
  const size_t targets = scene.meshes[instance.mesh].targets.size();
  const auto node = static_cast<uint32_t>(instance.morphNode);
  std::vector<float> weights(targets, 0.0f);
  if (node < scene.nodes.size()) {
    const std::vector<float>& rest = scene.nodes[node].weights;
    std::copy_n(rest.begin(), std::min(rest.size(), targets), weights.begin());
  }
  std::vector<float> sampled;
  for (const AnimationChannel& ch : scene.channels)
    if (ch.node == node && ch.path == AnimationPath::Weights && sampleWeights(ch, t, sampled))
      std::copy_n(sampled.begin(), std::min(sampled.size(), targets), weights.begin());
  return weights;
}

std::vector<glm::mat4> jointMatricesAt(const Scene& scene, const Instance& instance, float t) {
  if (instance.skin < 0 || static_cast<size_t>(instance.skin) >= scene.skins.size()) return {};
  const Skin& skin = scene.skins[static_cast<size_t>(instance.skin)];
  // Each node's world matrix once: joints share their ancestors (a chain of n joints would
  // otherwise take n^2 / 2 local transforms).
  std::unordered_map<uint32_t, glm::mat4> world;
  std::vector<uint32_t> chain;
  const auto worldOf = [&](uint32_t joint) {
    chain.clear();
    for (int64_t node = joint; node >= 0 && static_cast<size_t>(node) < scene.nodes.size() &&
                               chain.size() <= scene.nodes.size() && !world.count(static_cast<uint32_t>(node));
         node = scene.nodes[static_cast<size_t>(node)].parent)
      chain.push_back(static_cast<uint32_t>(node));
    glm::mat4 above(1.0f);
    if (!chain.empty()) {
      const int32_t parent = chain.back() < scene.nodes.size() ? scene.nodes[chain.back()].parent : -1;
      if (parent >= 0 && world.count(static_cast<uint32_t>(parent))) above = world[static_cast<uint32_t>(parent)];
    } else if (world.count(joint)) {
      return world[joint];
    }
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) above = world[*it] = above * scene.localTrsAt(*it, t).matrix();
    return above;
  };
  std::vector<glm::mat4> matrices(skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j)
    matrices[j] = worldOf(skin.joints[j]) *
                  (j < skin.inverseBindMatrices.size() ? skin.inverseBindMatrices[j] : glm::mat4(1.0f));
  return matrices;
}

Aabb deformedBoundsAt(const Scene& scene, const Instance& instance, float t) {
  Aabb box;
  for (const glm::vec3& p : deformedMeshAt(scene, instance, t).positions) box.grow(p);
  return box;
}

DeformedVertex deformVertex(const Mesh& mesh, uint32_t vertex, std::span<const float> morphWeights,
                            std::span<const glm::mat4> jointMatrices) {
  const glm::vec3 restNormal = vertex < mesh.normals.size() ? mesh.normals[vertex] : glm::vec3(0.0f, 0.0f, 1.0f);
  glm::vec3 p = mesh.positions[vertex], n = restNormal;
  for (size_t k = 0; k < mesh.targets.size() && k < morphWeights.size(); ++k) {
    const float w = morphWeights[k];
    if (w == 0.0f) continue;
    const MorphTarget& target = mesh.targets[k];
    if (vertex < target.positions.size()) p += w * target.positions[vertex];
    if (vertex < target.normals.size()) n += w * target.normals[vertex];
  }
  if (mesh.influences > 0 && !jointMatrices.empty()) {
    glm::mat4 blend(0.0f);
    for (uint32_t i = 0; i < mesh.influences; ++i) {
      const size_t at = size_t(vertex) * mesh.influences + i;
      const float w = mesh.weights[at];
      if (w != 0.0f && mesh.joints[at] < jointMatrices.size()) blend += w * jointMatrices[mesh.joints[at]];
    }
    p = glm::vec3(blend * glm::vec4(p, 1.0f));
    // det(M) M^-T is the matrix of the columns' pairwise cross products; its sign follows det.
    const glm::vec3 a(blend[0]), b(blend[1]), c(blend[2]);
    const glm::mat3 cofactor(glm::cross(b, c), glm::cross(c, a), glm::cross(a, b));
    n = (glm::dot(a, glm::cross(b, c)) < 0.0f ? -1.0f : 1.0f) * (cofactor * n);
  }
  const float length2 = glm::dot(n, n);
  n = length2 > 0.0f && std::isfinite(length2) ? n / std::sqrt(length2) : restNormal;
  return {p, n};
}

DeformedMesh deformedMeshAt(const Scene& scene, const Instance& instance, float t) {
  DeformedMesh out;
  if (instance.mesh >= scene.meshes.size()) return out;
  const Mesh& mesh = scene.meshes[instance.mesh];
  const std::vector<float> weights = morphWeightsAt(scene, instance, t);
  const std::vector<glm::mat4> joints = jointMatricesAt(scene, instance, t);
  out.positions.resize(mesh.positions.size());
  out.normals.resize(mesh.positions.size());
  for (uint32_t v = 0; v < mesh.positions.size(); ++v) {
    const DeformedVertex d = deformVertex(mesh, v, weights, joints);
    out.positions[v] = d.position;
    out.normals[v] = d.normal;
  }
  return out;
}

bool deformationIsAnimated(const Scene& scene, const Instance& instance) {
  if (instance.skin >= 0 && static_cast<size_t>(instance.skin) < scene.skins.size())
    for (const uint32_t joint : scene.skins[static_cast<size_t>(instance.skin)].joints)
      if (scene.isAnimated(joint)) return true;
  if (instance.morphNode >= 0)
    for (const AnimationChannel& ch : scene.channels)
      if (ch.path == AnimationPath::Weights && ch.node == static_cast<uint32_t>(instance.morphNode)) return true;
  return false;
}

bool deformationDiffers(const Scene& scene, const Instance& instance, float t0, float t1) {
  return morphWeightsAt(scene, instance, t0) != morphWeightsAt(scene, instance, t1) ||
         jointMatricesAt(scene, instance, t0) != jointMatricesAt(scene, instance, t1);
}

}  // namespace hmb::scene
