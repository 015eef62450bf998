#include "hmblur/engine_scene.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/matrix_decompose.hpp>

#include "hmblur/error.h"

namespace hmb {
namespace {

// The matrix as translation, rotation and scale; throws when it has shear or projection.
scene::Trs trsOf(const glm::mat4& m, const std::string& what) {
  scene::Trs trs;
  glm::vec3 skew;
  glm::vec4 perspective;
  if (!glm::decompose(m, trs.scale, trs.rotation, trs.translation, skew, perspective))
    throw Error(what + "'s world transform is singular or not finite");
  const glm::mat4 back = trs.matrix();
  float scale = 0.0f, error = 0.0f;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      scale = std::max(scale, std::abs(m[c][r]));
      error = std::max(error, std::abs(back[c][r] - m[c][r]));
    }
  if (!(error <= 1e-4f * std::max(scale, 1.0f)))
    throw Error(what + "'s world transform is not a translation, rotation and scale (it has shear or projection)");
  return trs;
}

// A node at its transform now, with two keys a frame: the previous transform at t - 1/fps.
// When the exposure is longer than a frame, a third key carries the motion on, straight, to the
// shutter's opening (the velocities the gathers read extrapolate the same way), so that rays at
// any shutter time (the hybrid's shutter rays) see it where the blur puts it.
void addMovingNode(scene::Scene& s, float t, const glm::mat4& now, const glm::mat4& previous, const std::string& what) {
  const scene::Trs a = trsOf(previous, what), b = trsOf(now, what);
  const auto node = static_cast<uint32_t>(s.nodes.size());
  scene::Node n;
  n.name = what;
  n.local = b;
  s.nodes.push_back(n);
  const float before = t - 1.0f / s.settings.fps;  // the time the methods take for the previous frame
  if (!(before < t)) throw Error("engine scene: frame time " + std::to_string(t) + " leaves no earlier frame");
  const float open = t - s.settings.exposure;
  // Past `before`, the previous transform continued: its share of the frame's step, more than 1.
  const float onward = open < before ? (t - open) / (t - before) : 1.0f;
  const auto channel = [&](scene::AnimationPath path, glm::vec4 from, glm::vec4 to, glm::vec4 opening) {
    scene::AnimationChannel c;
    c.node = node;
    c.path = path;
    c.times = {before, t};
    c.values = {from, to};
    if (open < before) {
      c.times.insert(c.times.begin(), open);
      c.values.insert(c.values.begin(), opening);
    }
    s.channels.push_back(std::move(c));
  };
  const auto onwardLinear = [&](glm::vec3 p, glm::vec3 q) { return glm::vec4(q + (p - q) * onward, 0.0f); };
  const glm::quat rotationAtOpen = glm::normalize(glm::slerp(b.rotation, a.rotation, onward));
  channel(scene::AnimationPath::Translation, glm::vec4(a.translation, 0.0f), glm::vec4(b.translation, 0.0f),
          onwardLinear(a.translation, b.translation));
  channel(scene::AnimationPath::Rotation, glm::vec4(a.rotation.x, a.rotation.y, a.rotation.z, a.rotation.w),
          glm::vec4(b.rotation.x, b.rotation.y, b.rotation.z, b.rotation.w),
          glm::vec4(rotationAtOpen.x, rotationAtOpen.y, rotationAtOpen.z, rotationAtOpen.w));
  channel(scene::AnimationPath::Scale, glm::vec4(a.scale, 0.0f), glm::vec4(b.scale, 0.0f),
          onwardLinear(a.scale, b.scale));
}

}  // namespace

EngineScene::EngineScene(float fps, float exposure, float softZExtent) {
  if (!(std::isfinite(fps) && fps > 0.0f)) throw Error("engine scene: fps must be a positive number");
  if (!(std::isfinite(exposure) && exposure > 0.0f)) throw Error("engine scene: exposure must be a positive number of seconds");
  if (!(std::isfinite(softZExtent) && softZExtent > 0.0f)) throw Error("engine scene: softZExtent must be positive");
  scene_.name = "engine";
  scene_.settings.fps = fps;
  scene_.settings.exposure = exposure;
  scene_.settings.softZExtent = softZExtent;
}

uint32_t EngineScene::addMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                              std::span<const uint32_t> indices, glm::vec3 color, bool doubleSided) {
  const std::string name = "mesh " + std::to_string(scene_.meshes.size());
  if (positions.empty() || indices.empty() || indices.size() % 3 != 0)
    throw Error("engine scene: " + name + " needs vertices and three indices a triangle");
  if (normals.size() != positions.size()) throw Error("engine scene: " + name + " needs one normal a vertex");
  for (const uint32_t i : indices)
    if (i >= positions.size()) throw Error("engine scene: " + name + " has an index past its vertices");
  scene::Mesh mesh;
  mesh.name = name;
  mesh.positions.assign(positions.begin(), positions.end());
  mesh.normals.assign(normals.begin(), normals.end());
  mesh.indices.assign(indices.begin(), indices.end());
  mesh.material = static_cast<uint32_t>(scene_.materials.size());
  scene::Material material;
  material.name = name;
  material.baseColorFactor = glm::vec4(color, 1.0f);
  material.doubleSided = doubleSided;
  scene_.materials.push_back(material);
  scene_.meshes.push_back(std::move(mesh));
  return static_cast<uint32_t>(scene_.meshes.size() - 1);
}

void EngineScene::setFrame(float t, std::span<const Instance> instances, const Camera& camera) {
  if (!std::isfinite(t)) throw Error("engine scene: the frame time must be finite");
  if (!(camera.yfov > 0.0f && camera.yfov < 3.14f && camera.znear > 0.0f && camera.zfar > camera.znear))
    throw Error("engine scene: the camera needs 0 < yfov < pi and 0 < znear < zfar");
  scene_.nodes.clear();
  scene_.channels.clear();
  scene_.instances.clear();
  for (size_t i = 0; i < instances.size(); ++i) {
    const Instance& in = instances[i];
    const std::string what = "instance " + std::to_string(i);
    if (in.mesh >= scene_.meshes.size()) throw Error("engine scene: " + what + " draws a mesh that was not added");
    if (in.objectId == 0) throw Error("engine scene: " + what + " has object id 0, the background's");
    addMovingNode(scene_, t, in.worldNow, in.worldPrevious, what);
    scene_.instances.push_back({in.mesh, static_cast<uint32_t>(scene_.nodes.size() - 1), in.objectId});
  }
  addMovingNode(scene_, t, camera.worldNow, camera.worldPrevious, "the camera");
  scene::Camera c;
  c.node = static_cast<int32_t>(scene_.nodes.size() - 1);
  c.yfov = camera.yfov;
  c.znear = camera.znear;
  c.zfar = camera.zfar;
  scene_.camera = c;
  scene_.settings.frameTime = t;
}

}  // namespace hmb
