// deriveDefaults: every rule here is relative to the scene's own size, so a scene modelled in
// millimetres and the same scene in kilometres get the same framing and proportional planes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "hmblur/scene.h"
#include "scenes/deformation.h"

namespace hmb::scene {
namespace {

bool finitePositive(float v) { return std::isfinite(v) && v > 0.0f; }

// Times at which the shutter of the frame (and the previous frame, for velocities) sees the
// scene: the near/far planes must hold everything visible over that interval.
std::vector<float> shutterSampleTimes(const Settings& s) {
  const float frameInterval = finitePositive(s.fps) ? 1.0f / s.fps : 0.0f;
  const float exposure = finitePositive(s.exposure) ? s.exposure : 0.0f;
  const float span = std::max(frameInterval, exposure);
  constexpr int kSamples = 5;
  std::vector<float> times;
  for (int i = 0; i < kSamples; ++i) times.push_back(s.frameTime - span * static_cast<float>(i) / (kSamples - 1));
  return times;
}

// World bounds of each instance, united over the given times (a deforming one deformed at each).
std::vector<Aabb> instanceBounds(const Scene& scene, const std::vector<float>& times) {
  std::vector<Aabb> meshBounds(scene.meshes.size());
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    for (const glm::vec3& p : scene.meshes[m].positions) meshBounds[m].grow(p);
  std::vector<Aabb> out;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh >= scene.meshes.size() || meshBounds[inst.mesh].empty()) continue;
    Aabb box;
    for (float t : times) {
      const Aabb local = inst.deforms() ? deformedBoundsAt(scene, inst, t) : meshBounds[inst.mesh];
      box.grow(transformed(local, scene.worldMatrixAt(inst.node, t)));
    }
    out.push_back(box);
  }
  return out;
}

float distanceToBox(const glm::vec3& p, const Aabb& box) { return glm::length(p - glm::clamp(p, box.min, box.max)); }

float farthestCornerDistance(const glm::vec3& p, const Aabb& box) {
  const glm::vec3 far = glm::max(glm::abs(p - box.min), glm::abs(p - box.max));
  return glm::length(far);
}

// Median world-space edge length over (a sample of) the instanced triangles: the size of the
// scene's geometric detail, independent of how far apart the objects are.
float medianEdgeLength(const Scene& scene, float t) {
  uint64_t triangles = scene.triangleCount();
  constexpr uint64_t kMaxSampled = 100000;
  const uint64_t stride = std::max<uint64_t>(1, triangles / kMaxSampled);
  std::vector<float> edges;
  uint64_t globalTriangle = 0;
  for (const Instance& inst : scene.instances) {
    if (inst.mesh >= scene.meshes.size()) continue;
    const Mesh& mesh = scene.meshes[inst.mesh];
    const glm::mat4 world = scene.worldMatrixAt(inst.node, t);
    // A deforming mesh as it is at t: a skeleton's scale or a morph changes its edges.
    const std::vector<glm::vec3> deformed = inst.deforms() ? deformedMeshAt(scene, inst, t).positions
                                                           : std::vector<glm::vec3>();
    const std::vector<glm::vec3>& positions = inst.deforms() ? deformed : mesh.positions;
    for (uint32_t tri = 0; tri < mesh.triangleCount(); ++tri, ++globalTriangle) {
      if (globalTriangle % stride != 0) continue;
      glm::vec3 p[3];
      bool valid = true;
      for (int k = 0; k < 3; ++k) {
        const uint32_t index = mesh.indices[tri * 3 + k];
        if (index >= positions.size()) {
          valid = false;
          break;
        }
        p[k] = glm::vec3(world * glm::vec4(positions[index], 1.0f));
      }
      if (!valid) continue;
      for (int k = 0; k < 3; ++k) {
        const float len = glm::length(p[k] - p[(k + 1) % 3]);
        if (finitePositive(len)) edges.push_back(len);
      }
    }
  }
  if (edges.empty()) return 0.0f;
  auto middle = edges.begin() + static_cast<std::ptrdiff_t>(edges.size() / 2);
  std::nth_element(edges.begin(), middle, edges.end());
  return *middle;
}

}  // namespace

void deriveDefaults(Scene& scene) {
  Settings& settings = scene.settings;
  const float t = settings.frameTime;

  const Aabb frameBounds = scene.boundsAt(t);
  const bool hasGeometry = !frameBounds.empty();
  const glm::vec3 center = hasGeometry ? frameBounds.center() : glm::vec3(0.0f);
  float radius = 0.5f * glm::length(frameBounds.extent());
  // An empty or point-like scene has no scale of its own: fall back to a unit sphere.
  if (!finitePositive(radius)) radius = 1.0f;

  if (!scene.camera) {
    Camera camera;
    // Fit the bounding sphere in the vertical field of view with a 10% margin. With an image
    // at least as wide as tall, the horizontal view is wider, so the sphere fits both ways.
    const float distance = 1.1f * radius / std::sin(0.5f * camera.yfov);
    const glm::vec3 direction = glm::normalize(glm::vec3(0.4f, 0.3f, 1.0f));
    Node node;
    node.name = "derived camera";
    node.local.translation = center + direction * distance;
    node.local.rotation = lookRotation(-direction);
    camera.node = static_cast<int32_t>(scene.nodes.size());
    scene.nodes.push_back(node);
    scene.camera = camera;
  }

  Camera& camera = *scene.camera;
  if (!(camera.yfov > 0.0f && camera.yfov < 3.1f)) camera.yfov = 0.8f;
  if (!(camera.znear >= 0.0f) || !std::isfinite(camera.znear)) camera.znear = 0.0f;
  if (!(camera.zfar >= 0.0f) || !std::isfinite(camera.zfar)) camera.zfar = 0.0f;
  if (camera.znear == 0.0f || camera.zfar == 0.0f) {
    const glm::mat4 cameraWorld =
        camera.node >= 0 ? scene.worldMatrixAt(static_cast<uint32_t>(camera.node), t) : glm::mat4(1.0f);
    const glm::vec3 eye(cameraWorld[3]);
    // Far: the farthest corner of anything seen during the shutter, with a 50% margin so
    // that depth never clips at the far plane. Near: half the distance to the closest
    // object's box (depth = distance * cos(off-axis angle), and half covers any sane field of
    // view); 0 when the camera sits inside some object's box (a room), where only the floor
    // applies. The floor far * 1e-5 keeps the depth range within float precision.
    float farthest = 0.0f;
    float nearest = std::numeric_limits<float>::infinity();
    for (const Aabb& box : instanceBounds(scene, shutterSampleTimes(settings))) {
      farthest = std::max(farthest, farthestCornerDistance(eye, box));
      nearest = std::min(nearest, distanceToBox(eye, box));
    }
    float derivedFar = 1.5f * farthest;
    if (!finitePositive(derivedFar)) derivedFar = 1.5f * (glm::length(eye - center) + radius);
    if (!finitePositive(derivedFar)) derivedFar = 2.0f * radius;
    float derivedNear = derivedFar * 1e-5f;
    if (std::isfinite(nearest)) derivedNear = std::max(derivedNear, 0.5f * nearest);

    if (camera.zfar == 0.0f) camera.zfar = std::max(derivedFar, camera.znear * 10.0f);
    if (camera.znear == 0.0f) camera.znear = std::min(derivedNear, camera.zfar * 0.5f);
  }
  if (!(camera.znear < camera.zfar)) camera.zfar = camera.znear * 10.0f;

  if (!(settings.softZExtent > 0.0f) || !std::isfinite(settings.softZExtent)) {
    // SOFT_Z_EXTENT is the depth tolerance under which two surfaces count as one layer, so it
    // follows the size of the scene's geometric detail: half the median edge length. Rooms
    // modelled with ~5-10 cm triangles give ~3 cm; a densely detailed interior (~1 cm
    // triangles) gives ~5 mm, the paper's values. Clamped to [2e-4, 1e-2] of the bounding
    // radius so that a few huge or tiny triangles cannot push it out of proportion.
    const float median = medianEdgeLength(scene, t);
    const float fromDetail = finitePositive(median) ? 0.5f * median : 0.005f * radius;
    settings.softZExtent = std::clamp(fromDetail, 2e-4f * radius, 1e-2f * radius);
  }

  const float lightLength = glm::length(scene.light.direction);
  if (finitePositive(lightLength))
    scene.light.direction /= lightLength;
  else
    scene.light.direction = glm::vec3(0.0f, -1.0f, 0.0f);
}

}  // namespace hmb::scene
