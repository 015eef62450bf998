#include "hmblur/scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "scenes/deformation.h"

namespace hmb::scene {
namespace {

glm::quat toQuat(const glm::vec4& xyzw) { return glm::quat(xyzw.w, xyzw.x, xyzw.y, xyzw.z); }

glm::quat normalizedOrIdentity(const glm::quat& q) {
  const float len = glm::length(q);
  if (!(len > 0.0f) || !std::isfinite(len)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return q / len;
}

// Spherical interpolation along the shorter arc; falls back to a normalized lerp when the
// two rotations are nearly equal, where slerp's division by sin(angle) loses precision.
glm::quat shortestSlerp(glm::quat a, glm::quat b, float u) {
  a = normalizedOrIdentity(a);
  b = normalizedOrIdentity(b);
  float cosAngle = glm::dot(a, b);
  if (cosAngle < 0.0f) {
    b = -b;
    cosAngle = -cosAngle;
  }
  if (cosAngle > 0.9995f) return normalizedOrIdentity(a * (1.0f - u) + b * u);
  const float angle = std::acos(std::min(cosAngle, 1.0f));
  const float sinAngle = std::sin(angle);
  const float wa = std::sin((1.0f - u) * angle) / sinAngle;
  const float wb = std::sin(u * angle) / sinAngle;
  return normalizedOrIdentity(a * wa + b * wb);
}

// Samples one channel at t. Returns false when the channel is malformed (never crash on
// data that slipped past validation).
bool sampleChannel(const AnimationChannel& ch, float t, glm::vec4& out, bool isRotation) {
  const size_t keys = ch.times.size();
  if (keys == 0) return false;
  const bool cubic = ch.interpolation == Interpolation::CubicSpline;
  const size_t stride = cubic ? 3 : 1;
  const size_t valueOffset = cubic ? 1 : 0;  // the value sits between the two tangents
  if (ch.values.size() < keys * stride) return false;
  auto keyValue = [&](size_t k) { return ch.values[k * stride + valueOffset]; };

  const KeySegment segment = keySegment(ch.times, t);
  if (segment.k0 == segment.k1) {
    out = keyValue(segment.k0);
    return true;
  }
  const size_t k0 = segment.k0, k1 = segment.k1;
  const float dt = segment.dt, u = segment.u;

  switch (ch.interpolation) {
    case Interpolation::Step: out = keyValue(k0); return true;
    case Interpolation::Linear:
      if (isRotation) {
        const glm::quat q = shortestSlerp(toQuat(keyValue(k0)), toQuat(keyValue(k1)), u);
        out = glm::vec4(q.x, q.y, q.z, q.w);
      } else {
        out = glm::mix(keyValue(k0), keyValue(k1), u);
      }
      return true;
    case Interpolation::CubicSpline: {
      out = cubicSpline(ch.values[k0 * 3 + 1], ch.values[k0 * 3 + 2], ch.values[k1 * 3 + 1], ch.values[k1 * 3 + 0], u,
                        dt);
      if (isRotation) {
        const glm::quat q = normalizedOrIdentity(toQuat(out));
        out = glm::vec4(q.x, q.y, q.z, q.w);
      }
      return true;
    }
  }
  return false;
}

}  // namespace

KeySegment keySegment(const std::vector<float>& times, float t) {
  const size_t keys = times.size();
  if (keys == 0) return {};
  if (!(t > times.front())) return {0, 0, 0.0f, 0.0f};  // also catches NaN t
  if (t >= times.back()) return {keys - 1, keys - 1, 0.0f, 0.0f};
  // First key strictly after t; the segment is [k0, k0 + 1].
  const size_t k1 = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin());
  const size_t k0 = k1 - 1;
  const float dt = times[k1] - times[k0];
  const float u = dt > 0.0f ? std::clamp((t - times[k0]) / dt, 0.0f, 1.0f) : 1.0f;
  return {k0, k1, u, dt};
}

Scene singleMeshScene(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
  Scene scene;
  scene.name = "triangles";
  Mesh mesh;
  mesh.name = "triangles";
  mesh.positions = positions;
  mesh.normals.assign(positions.size(), glm::vec3(0.0f, 0.0f, 1.0f));
  mesh.indices = indices;
  scene.meshes.push_back(std::move(mesh));
  scene.materials.push_back({});
  scene.nodes.push_back({});
  scene.instances.push_back({0, 0, 1});
  return scene;
}

glm::quat lookRotation(const glm::vec3& forward) {
  const glm::vec3 back = -glm::normalize(forward);
  // Looking straight up or down: any horizontal "up" will do, -Z keeps the result stable.
  glm::vec3 up(0.0f, 1.0f, 0.0f);
  if (std::abs(glm::dot(up, back)) > 0.999f) up = glm::vec3(0.0f, 0.0f, -1.0f);
  const glm::vec3 right = glm::normalize(glm::cross(up, back));
  return glm::normalize(glm::quat_cast(glm::mat3(right, glm::cross(back, right), back)));
}

glm::mat4 Trs::matrix() const {
  const glm::mat4 t = glm::translate(glm::mat4(1.0f), translation);
  const glm::mat4 r = glm::mat4_cast(normalizedOrIdentity(rotation));
  return glm::scale(t * r, scale);
}

Trs Scene::localTrsAt(uint32_t node, float t) const {
  if (node >= nodes.size()) return Trs{};
  Trs trs = nodes[node].local;
  for (const AnimationChannel& ch : channels) {
    if (ch.node != node || ch.path == AnimationPath::Weights) continue;
    glm::vec4 v;
    if (!sampleChannel(ch, t, v, ch.path == AnimationPath::Rotation)) continue;
    switch (ch.path) {
      case AnimationPath::Translation: trs.translation = glm::vec3(v); break;
      case AnimationPath::Rotation: trs.rotation = normalizedOrIdentity(toQuat(v)); break;
      case AnimationPath::Scale: trs.scale = glm::vec3(v); break;
      case AnimationPath::Weights: break;  // not a transform (scenes/deformation.h)
    }
  }
  return trs;
}

glm::mat4 Scene::worldMatrixAt(uint32_t node, float t) const {
  glm::mat4 world(1.0f);
  // At most nodes.size() steps: a cycle (which the loader rejects) cannot loop forever.
  int64_t current = node;
  for (size_t steps = 0; current >= 0 && static_cast<size_t>(current) < nodes.size() && steps < nodes.size(); ++steps) {
    world = localTrsAt(static_cast<uint32_t>(current), t).matrix() * world;
    current = nodes[static_cast<size_t>(current)].parent;
  }
  return world;
}

bool Scene::isAnimated(uint32_t node) const {
  int64_t current = node;
  for (size_t steps = 0; current >= 0 && static_cast<size_t>(current) < nodes.size() && steps < nodes.size(); ++steps) {
    for (const AnimationChannel& ch : channels)
      if (ch.node == static_cast<uint32_t>(current) && ch.path != AnimationPath::Weights) return true;
    current = nodes[static_cast<size_t>(current)].parent;
  }
  return false;
}

Aabb Scene::boundsAt(float t) const {
  std::vector<Aabb> meshBounds(meshes.size());
  for (size_t m = 0; m < meshes.size(); ++m)
    for (const glm::vec3& p : meshes[m].positions) meshBounds[m].grow(p);
  Aabb bounds;
  for (const Instance& inst : instances) {
    if (inst.mesh >= meshes.size()) continue;
    const Aabb box = inst.deforms() ? deformedBoundsAt(*this, inst, t) : meshBounds[inst.mesh];
    bounds.grow(transformed(box, worldMatrixAt(inst.node, t)));
  }
  return bounds;
}

bool Scene::hasDeformation() const {
  return std::any_of(instances.begin(), instances.end(), [](const Instance& i) { return i.deforms(); });
}

uint64_t Scene::triangleCount() const {
  uint64_t count = 0;
  for (const Instance& inst : instances)
    if (inst.mesh < meshes.size()) count += meshes[inst.mesh].triangleCount();
  return count;
}

}  // namespace hmb::scene
