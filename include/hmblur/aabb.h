// Axis-aligned bounding box: scene bounds now, BVH nodes later.
#pragma once

#include <algorithm>
#include <limits>

#include <glm/glm.hpp>

namespace hmb {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
  void grow(const glm::vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void grow(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : max - min; }
  glm::vec3 center() const { return empty() ? glm::vec3(0.0f) : 0.5f * (min + max); }
  float surfaceArea() const {
    const glm::vec3 e = extent();
    return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  bool contains(const glm::vec3& p) const {
    return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x <= max.x && p.y <= max.y && p.z <= max.z;
  }
};

// Bounds of a box after an affine transform (transforms its eight corners).
inline Aabb transformed(const Aabb& box, const glm::mat4& m) {
  Aabb out;
  if (box.empty()) return out;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner((i & 1) ? box.max.x : box.min.x, (i & 2) ? box.max.y : box.min.y,
                           (i & 4) ? box.max.z : box.min.z);
    out.grow(glm::vec3(m * glm::vec4(corner, 1.0f)));
  }
  return out;
}

}  // namespace hmb
