// Robust ray-box and ray-triangle tests shared by the reference traversal and brute force, so
// that the two can only differ in which triangles they test.
#pragma once

#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#include "hmblur/aabb.h"

namespace hmb::bvh {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // need not be unit; t is in units of its length
  float tMin = 0.0f;
  float tMax = std::numeric_limits<float>::infinity();
};

// Per-ray constants of both tests, computed once per ray.
struct PreparedRay {
  explicit PreparedRay(const Ray& ray);

  glm::vec3 origin;
  glm::vec3 direction;
  glm::vec3 inverseDirection;  // 1 / direction: +-inf for a zero component, by its sign
  bool valid;                  // false for a zero or non-finite direction: it hits nothing
  // Watertight triangle test (Woop, Benthin, Wald 2013): kz is the direction's dominant axis,
  // kx and ky the other two in an order that keeps the triangle's winding; the shear maps the
  // direction to +z with unit length in z.
  int kx, ky, kz;
  float shearX, shearY, shearZ;
};

// Parametric interval of the ray inside the box, clipped to [tMin, tMax]; true when it is not
// empty, with its entry in tNear. Planes are selected by the direction's sign (so 1/-0 picks
// the right ones), and a 0 * inf from a ray lying in a slab's boundary plane (NaN) leaves the
// interval as it was: such a ray counts as inside that slab. The far end is widened by
// kBoxSlack (relative), which covers this test's rounding (Ize 2013 needs 2 * gamma(3)) and the
// triangle test's rounding of t, so a triangle hit is never culled by its own leaf's box.
bool intersectBox(const PreparedRay& ray, const Aabb& box, float tMin, float tMax, float& tNear);

inline constexpr float kBoxSlack = 1.0f / 65536.0f;

// The distance along the ray to the plane of a triangle it hits, to float precision. The
// watertight test's t (its edge functions' weighted mean of the vertices' distances) loses
// that where the products of distant vertices cancel: a long thin triangle near the origin was
// hit up to 1e-3 relative from the exact distance on a CAD model. Traversals order candidates
// by the watertight t and take this for the closest one, once per ray. A triangle whose
// largest angle is within kSliverSine of 180 degrees (its normal is rounding) or a ray in its
// plane keeps `shearedT`.
float planeHitDistance(const PreparedRay& ray, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                       float shearedT);
inline constexpr float kSliverSine = 1.0f / 1024.0f;

struct TriangleHit {
  float t;
  float u;  // barycentric weight of v1
  float v;  // barycentric weight of v2
};

// Watertight ray-triangle test, both sides, any t (the caller checks the range). A ray through
// an edge or vertex shared by two triangles hits at least one of them: edge functions of a
// shared edge are exact negatives in both, and exact zeros are recomputed in double so their
// sign is right. Degenerate triangles and rays in the triangle's plane (determinant 0) miss.
bool intersectTriangle(const PreparedRay& ray, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                       TriangleHit& hit);

}  // namespace hmb::bvh
