#include "bvh/reference_traversal.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace hmb::bvh {
namespace {

Hit missFor(const Ray& ray) { return Hit{ray.tMax, 0.0f, 0.0f, HMB_NO_HIT, HMB_NO_HIT, 0, 0, 0}; }

// The closest hit's distance from its triangle's plane (planeHitDistance), kept in [tMin, tMax].
void refineDistance(const PreparedRay& prepared, const Ray& ray, const TriangleList& triangles, Hit& best) {
  if (best.triangle == HMB_NO_HIT) return;
  const auto [v0, v1, v2] = triangles.vertices(best.triangle);
  best.t = std::clamp(planeHitDistance(prepared, v0, v1, v2, best.t), ray.tMin, ray.tMax);
}

// Tests one triangle and keeps it when it comes before the best hit so far.
void testTriangle(const PreparedRay& prepared, const Ray& ray, const TriangleList& triangles, uint32_t triangle,
                  const TraceOptions& options, Hit& best) {
  const uint32_t objectId = triangles.objectId(triangle);
  if (objectId == options.ignoreObjectId) return;
  const auto [v0, v1, v2] = triangles.vertices(triangle);
  TriangleHit hit;
  if (!intersectTriangle(prepared, v0, v1, v2, hit)) return;
  if (!(hit.t >= ray.tMin)) return;
  if (hit.t < best.t || (hit.t == best.t && triangle < best.triangle))
    best = Hit{hit.t, hit.u, hit.v, triangle, objectId, 0, 0, 0};
}

}  // namespace

Hit closestHit(const Bvh& bvh, const TriangleList& triangles, const Ray& ray, const TraceOptions& options) {
  Hit best = missFor(ray);
  const PreparedRay prepared(ray);
  if (!prepared.valid || bvh.nodes.empty()) return best;
  float rootNear;
  if (!intersectBox(prepared, boundsOf(bvh.nodes[HMB_BVH_ROOT]), ray.tMin, best.t, rootNear)) return best;
  // Nodes still to visit with their entry t; one whose entry is now behind the best hit is skipped.
  std::vector<std::pair<uint32_t, float>> stack{{HMB_BVH_ROOT, rootNear}};
  while (!stack.empty()) {
    const auto [index, entry] = stack.back();
    stack.pop_back();
    if (entry > best.t + std::abs(best.t) * kBoxSlack) continue;
    const Node& node = bvh.nodes[index];
    if (isLeaf(node)) {
      for (uint32_t i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i)
        testTriangle(prepared, ray, triangles, bvh.primitiveIndices[i], options, best);
      continue;
    }
    const uint32_t left = node.leftOrFirst, right = left + 1;
    float leftNear, rightNear;
    const bool hitLeft = intersectBox(prepared, boundsOf(bvh.nodes[left]), ray.tMin, best.t, leftNear);
    const bool hitRight = intersectBox(prepared, boundsOf(bvh.nodes[right]), ray.tMin, best.t, rightNear);
    // The nearer child goes on top, so it is visited first.
    if (hitLeft && hitRight) {
      const bool leftFirst = leftNear <= rightNear;
      stack.push_back(leftFirst ? std::pair{right, rightNear} : std::pair{left, leftNear});
      stack.push_back(leftFirst ? std::pair{left, leftNear} : std::pair{right, rightNear});
    } else if (hitLeft) {
      stack.push_back({left, leftNear});
    } else if (hitRight) {
      stack.push_back({right, rightNear});
    }
  }
  refineDistance(prepared, ray, triangles, best);
  return best;
}

Hit bruteForceClosestHit(const TriangleList& triangles, const Ray& ray, const TraceOptions& options) {
  Hit best = missFor(ray);
  const PreparedRay prepared(ray);
  if (!prepared.valid) return best;
  for (uint32_t t = 0; t < triangles.triangleCount(); ++t) testTriangle(prepared, ray, triangles, t, options, best);
  refineDistance(prepared, ray, triangles, best);
  return best;
}

ExactHit exactClosestHit(const TriangleList& triangles, const Ray& ray, double grazeMargin) {
  ExactHit out;
  const glm::dvec3 o(ray.origin), d(ray.direction);
  for (uint32_t triangle = 0; triangle < triangles.triangleCount(); ++triangle) {
    const auto [v0, v1, v2] = triangles.vertices(triangle);
    const glm::dvec3 p0(v0), e1 = glm::dvec3(v1) - p0, e2 = glm::dvec3(v2) - p0;
    const glm::dvec3 p = glm::cross(d, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0 || !std::isfinite(det)) continue;
    const glm::dvec3 s = o - p0, q = glm::cross(s, e1);
    const double u = glm::dot(s, p) / det, v = glm::dot(d, q) / det, t = glm::dot(e2, q) / det;
    if (!(t >= double(ray.tMin)) || !(t <= double(ray.tMax))) continue;
    const double margin = std::min({u, v, 1.0 - u - v});
    if (margin >= 0.0) out.t = std::min(out.t, t);
    if (std::abs(margin) <= grazeMargin) out.grazeT = std::min(out.grazeT, t);
  }
  return out;
}

}  // namespace hmb::bvh
