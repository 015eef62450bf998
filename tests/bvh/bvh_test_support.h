// Meshes, rays, a median-split builder and a structural checker shared by the BVH tests.
#pragma once

#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "bvh/ray_intersection.h"
#include "bvh/reference_traversal.h"
#include "bvh/triangle_list.h"
#include "hmblur/aabb.h"
#include "hmblur/scene.h"

namespace hmb::bvh::test {

// Owns what a TriangleList views.
struct TriangleMesh {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<uint32_t> objectIds;  // one per triangle

  TriangleList view() const { return {positions, indices, objectIds}; }
  uint32_t triangleCount() const { return static_cast<uint32_t>(indices.size() / 3); }
  void addTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint32_t objectId);
  void append(const scene::Mesh& mesh, const glm::mat4& transform, uint32_t objectId);
  Aabb bounds() const;
};

// `count` triangles: a first vertex in the unit cube, the other two within +-size of it per axis;
// object ids 1..7 in turn.
TriangleMesh randomSoup(uint32_t count, float size, uint32_t seed);
// Random boxes, a tenth of them stacked on one centre (equal Morton codes), and where asked a
// few empty ones.
std::vector<Aabb> randomBoxes(uint32_t count, uint32_t seed, bool someEmpty = false);
// (cells x cells) unit quads in the z = 0 plane from (0, 0), integer vertices shared by index,
// each quad split along a random diagonal.
TriangleMesh grid(uint32_t cells, uint32_t seed);
// Closed mesh: a cube's six faces tessellated into (cells x cells) quads with every vertex
// shared by index (no seams), pushed onto the unit sphere.
TriangleMesh cubeSphere(uint32_t cells);
// World-space triangles of every instance of a scene at time t, object id per instance.
TriangleMesh sceneTriangles(const scene::Scene& scene, float t);

Bvh buildSah(const TriangleMesh& mesh, uint32_t maxLeafSize = 4);
// A plain top-down build splitting at the median centroid of the widest centroid axis: the
// baseline the SAH build must beat.
Bvh buildMedianSplit(std::span<const Aabb> bounds, std::span<const glm::vec3> centroids, uint32_t maxLeafSize);

// Empty when the BVH is a well-formed tree over primitives 0..n-1: every node reached once,
// every primitive in exactly one leaf, leaves of 1..maxLeafSize primitives, every node's
// bounds containing its children's or its primitives'. Otherwise the first problem found.
std::string structuralProblem(const Bvh& bvh, std::span<const Aabb> bounds, uint32_t maxLeafSize);

glm::vec3 randomUnitVector(std::mt19937& rng);
glm::vec3 randomPointIn(const Aabb& box, std::mt19937& rng);
// A uniformly random point of the triangle (barycentric).
glm::vec3 randomPointOnTriangle(const TriangleList& triangles, uint32_t triangle, std::mt19937& rng);

// A mix of rays for a mesh: half from random points around it in random directions, half
// aimed at random points of random triangles from outside; some with finite [tMin, tMax].
std::vector<Ray> mixedRays(const TriangleMesh& mesh, uint32_t count, uint32_t seed);

// BVH traversal against brute force over the same rays: both miss, or the same triangle with
// t, u and v within 1e-5 relative.
struct Agreement {
  uint32_t rays = 0;
  uint32_t hits = 0;  // rays brute force saw hit something
  uint32_t mismatches = 0;
  std::string firstMismatch;
};
Agreement compareWithBruteForce(const Bvh& bvh, const TriangleList& triangles, std::span<const Ray> rays,
                                const TraceOptions& options = {});

}  // namespace hmb::bvh::test
