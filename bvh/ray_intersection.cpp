// Built with -ffp-contract=off (bvh/CMakeLists.txt): a fused a * b - c * d is not the exact
// negative of the fused d * c - b * a, which the watertight test relies on.
#include "bvh/ray_intersection.h"

#include <cmath>
#include <utility>

namespace hmb::bvh {

PreparedRay::PreparedRay(const Ray& ray) : origin(ray.origin), direction(ray.direction) {
  const glm::vec3& d = ray.direction;
  inverseDirection = 1.0f / d;
  valid = std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z) && d != glm::vec3(0.0f);
  const glm::vec3 a = glm::abs(d);
  kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
  kx = (kz + 1) % 3;
  ky = (kx + 1) % 3;
  if (d[kz] < 0.0f) std::swap(kx, ky);
  shearX = d[kx] / d[kz];
  shearY = d[ky] / d[kz];
  shearZ = 1.0f / d[kz];
}

bool intersectBox(const PreparedRay& ray, const Aabb& box, float tMin, float tMax, float& tNear) {
  float near = tMin, far = tMax;
  for (int axis = 0; axis < 3; ++axis) {
    const bool negative = std::signbit(ray.inverseDirection[axis]);
    const float entryPlane = negative ? box.max[axis] : box.min[axis];
    const float exitPlane = negative ? box.min[axis] : box.max[axis];
    const float entry = (entryPlane - ray.origin[axis]) * ray.inverseDirection[axis];
    const float exit = (exitPlane - ray.origin[axis]) * ray.inverseDirection[axis];
    // Comparisons with NaN are false, so a NaN bound keeps the current one.
    near = entry > near ? entry : near;
    far = exit < far ? exit : far;
  }
  far += std::abs(far) * kBoxSlack;
  tNear = near;
  return near <= far;
}

bool intersectTriangle(const PreparedRay& ray, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                       TriangleHit& hit) {
  // Vertices relative to the origin, sheared so that the ray is the +z axis.
  const glm::vec3 a = v0 - ray.origin, b = v1 - ray.origin, c = v2 - ray.origin;
  const float ax = a[ray.kx] - ray.shearX * a[ray.kz], ay = a[ray.ky] - ray.shearY * a[ray.kz];
  const float bx = b[ray.kx] - ray.shearX * b[ray.kz], by = b[ray.ky] - ray.shearY * b[ray.kz];
  const float cx = c[ray.kx] - ray.shearX * c[ray.kz], cy = c[ray.ky] - ray.shearY * c[ray.kz];
  // Edge functions: twice the signed areas of the sub-triangles at the ray, one per vertex.
  float u = cx * by - cy * bx;  // edge v1-v2, weight of v0
  float v = ax * cy - ay * cx;  // edge v2-v0, weight of v1
  float w = bx * ay - by * ax;  // edge v0-v1, weight of v2
  // A non-zero float result has the sign of the exact value; a zero may not, so it is redone
  // with exact products.
  if (u == 0.0f || v == 0.0f || w == 0.0f) {
    const double dax = ax, day = ay, dbx = bx, dby = by, dcx = cx, dcy = cy;
    u = static_cast<float>(dcx * dby - dcy * dbx);
    v = static_cast<float>(dax * dcy - day * dcx);
    w = static_cast<float>(dbx * day - dby * dax);
  }
  if ((u < 0.0f || v < 0.0f || w < 0.0f) && (u > 0.0f || v > 0.0f || w > 0.0f)) return false;
  const float det = u + v + w;
  if (det == 0.0f) return false;
  const float az = ray.shearZ * a[ray.kz], bz = ray.shearZ * b[ray.kz], cz = ray.shearZ * c[ray.kz];
  const float inverseDet = 1.0f / det;
  const float t = (u * az + v * bz + w * cz) * inverseDet;
  hit = TriangleHit{t, v * inverseDet, w * inverseDet};
  return true;
}

float planeHitDistance(const PreparedRay& ray, const glm::vec3& v0, const glm::vec3& v1, const glm::vec3& v2,
                        float shearedT) {
  // The normal is the cross product of the two edges at the largest angle (opposite the longest
  // edge: at least 60 degrees, so well conditioned), and the plane passes through their vertex;
  // edges and vertex minus origin are exact for nearby floats.
  const glm::vec3 edge0 = v1 - v0, edge1 = v2 - v1, edge2 = v0 - v2;
  const float length0 = glm::dot(edge0, edge0), length1 = glm::dot(edge1, edge1), length2 = glm::dot(edge2, edge2);
  glm::vec3 normal, vertex;
  float lengths;
  if (length0 >= length1 && length0 >= length2) {
    normal = glm::cross(edge1, edge2), vertex = v2, lengths = length1 * length2;
  } else if (length1 >= length2) {
    normal = glm::cross(edge2, edge0), vertex = v0, lengths = length2 * length0;
  } else {
    normal = glm::cross(edge0, edge1), vertex = v1, lengths = length0 * length1;
  }
  const float towards = glm::dot(normal, ray.direction);
  if (!(towards != 0.0f && std::isfinite(towards) && glm::dot(normal, normal) >= kSliverSine * kSliverSine * lengths))
    return shearedT;
  return glm::dot(normal, vertex - ray.origin) / towards;
}

}  // namespace hmb::bvh
