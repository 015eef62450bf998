#include "bvh/triangle_list.h"

namespace hmb::bvh {

PrimitiveBounds triangleBounds(const TriangleList& triangles) {
  PrimitiveBounds out;
  const uint32_t count = triangles.triangleCount();
  out.bounds.resize(count);
  out.centroids.resize(count);
  for (uint32_t t = 0; t < count; ++t) {
    Aabb& box = out.bounds[t];
    for (const glm::vec3& p : triangles.vertices(t)) box.grow(p);
    out.centroids[t] = box.center();
  }
  return out;
}

}  // namespace hmb::bvh
