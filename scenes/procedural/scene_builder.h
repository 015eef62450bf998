// Small helpers to assemble the reference scenes: materials, objects (one node and one object
// id each), keyframed motion and a look-at camera, plus a portable deterministic RNG.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hmblur/scene.h"

namespace hmb::scene::procedural {

Trs makeTrs(const glm::vec3& translation, const glm::quat& rotation = glm::quat(1.0f, 0.0f, 0.0f, 0.0f),
            const glm::vec3& scale = glm::vec3(1.0f));

// SplitMix64: the same sequence on every platform and standard library.
class Rng {
 public:
  explicit Rng(uint64_t seed) : state_(seed) {}
  uint64_t next();
  float uniform(float lo, float hi);  // [lo, hi)
  uint32_t below(uint32_t n);         // [0, n)

 private:
  uint64_t state_;
};

class SceneBuilder {
 public:
  explicit SceneBuilder(std::string name);

  uint32_t material(std::string name, const glm::vec3& linearColor, int32_t texture = -1, bool doubleSided = false);
  int32_t texture(Texture texture);
  uint32_t mesh(Mesh mesh);

  // A node without geometry (a pivot or the camera).
  uint32_t node(std::string name, const Trs& rest, int32_t parent = -1);
  // A node drawing `mesh`, as a new object with its own id.
  uint32_t object(std::string name, uint32_t mesh, const Trs& rest, int32_t parent = -1);
  // One more mesh drawn by an existing object's node, sharing its id.
  void addToObject(uint32_t node, uint32_t mesh);

  void keys(uint32_t node, AnimationPath path, Interpolation interpolation, std::vector<float> times,
            std::vector<glm::vec4> values);
  void translationKeys(uint32_t node, const std::vector<float>& times, const std::vector<glm::vec3>& positions,
                       Interpolation interpolation = Interpolation::Linear);
  // Constant spin about `axis` (applied after the rest rotation) over [start, end], keyed every
  // quarter turn so that shortest-path slerp follows the intended direction.
  void spin(uint32_t node, const glm::vec3& axis, float turnsPerSecond, float start, float end);

  // A perspective camera at `eye` looking at `target`; returns its node.
  uint32_t camera(const glm::vec3& eye, const glm::vec3& target, float yfov);

  Scene& scene() { return scene_; }
  Scene finish() { return std::move(scene_); }

 private:
  Scene scene_;
  uint32_t nextObjectId_ = 1;
};

}  // namespace hmb::scene::procedural
