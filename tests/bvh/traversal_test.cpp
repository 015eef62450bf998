// The reference traversal against brute force over every triangle: random soups, procedural
// meshes, rays along axes, rays through shared edges and vertices (which must hit), degenerate
// and duplicated triangles, the ignore-object option, and tiny or empty inputs.
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "bvh/reference_traversal.h"
#include "scenes/procedural/mesh_builders.h"
#include "tests/bvh/bvh_test_support.h"

namespace hmb::bvh::test {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Same answers as brute force, and enough hits that the comparison means something.
void expectAgreement(const TriangleMesh& mesh, std::span<const Ray> rays, double minHitFraction,
                     const TraceOptions& options = {}) {
  const Bvh bvh = buildSah(mesh);
  ASSERT_EQ(structuralProblem(bvh, triangleBounds(mesh.view()).bounds, 4), "");
  const Agreement agreement = compareWithBruteForce(bvh, mesh.view(), rays, options);
  EXPECT_EQ(agreement.mismatches, 0u) << agreement.firstMismatch;
  EXPECT_GE(agreement.hits, minHitFraction * agreement.rays) << agreement.hits << " of " << agreement.rays;
}

glm::mat4 randomRigidTransform(std::mt19937& rng) {
  std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
  return glm::translate(glm::mat4(1.0f), randomUnitVector(rng) * 3.0f) *
         glm::rotate(glm::mat4(1.0f), angle(rng), randomUnitVector(rng));
}

void transform(TriangleMesh& mesh, const glm::mat4& m) {
  for (glm::vec3& p : mesh.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
}

TEST(ReferenceTraversal, RandomSoupsAgreeWithBruteForce) {
  for (uint32_t seed : {1u, 2u, 3u})
    for (float size : {0.03f, 0.3f}) {
      const TriangleMesh soup = randomSoup(2000, size, seed);
      expectAgreement(soup, mixedRays(soup, 4000, seed + 100), 0.4);
    }
}

TEST(ReferenceTraversal, ProceduralMeshesAgreeWithBruteForce) {
  TriangleMesh sphere, torus, both;
  sphere.append(scene::procedural::makeSphere(1.0f, 48, 24, 0), glm::mat4(1.0f), 1);
  torus.append(scene::procedural::makeTorus(1.0f, 0.3f, 64, 24, 0), glm::mat4(1.0f), 2);
  both.append(scene::procedural::makeSphere(1.0f, 32, 16, 0), glm::mat4(1.0f), 1);
  both.append(scene::procedural::makeTorus(1.5f, 0.2f, 48, 16, 0), glm::rotate(glm::mat4(1.0f), 0.7f, {1, 0, 0}), 2);
  both.append(scene::procedural::makeBox({0.3f, 0.3f, 0.3f}, 0), glm::mat4(1.0f), 3);  // inside the sphere
  expectAgreement(sphere, mixedRays(sphere, 4000, 7), 0.5);
  expectAgreement(torus, mixedRays(torus, 4000, 8), 0.5);
  expectAgreement(both, mixedRays(both, 4000, 9), 0.5);
}

// Directions exactly along +-x, +-y, +-z, from origins whose other coordinates often sit exactly
// on vertex coordinates: in the planes of axis-aligned faces and boxes, through their edges.
std::vector<Ray> axisRays(const TriangleMesh& mesh, uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  Aabb around = mesh.bounds();
  around.min -= 0.5f, around.max += 0.5f;
  std::uniform_int_distribution<size_t> pickVertex(0, mesh.positions.size() - 1);
  std::vector<Ray> rays;
  for (uint32_t i = 0; i < count; ++i) {
    Ray ray{randomPointIn(around, rng), glm::vec3(0.0f)};
    const int axis = static_cast<int>(i % 3);
    const float sign = (i / 3) % 2 ? 1.0f : -1.0f;
    ray.direction[axis] = sign;
    if (i % 4 != 0) {  // snap the other coordinates to a vertex's, one or both
      const glm::vec3 v = mesh.positions[pickVertex(rng)];
      ray.origin[(axis + 1) % 3] = v[(axis + 1) % 3];
      if (i % 4 != 1) ray.origin[(axis + 2) % 3] = v[(axis + 2) % 3];
    }
    if (i % 7 == 0) ray.direction[(axis + 1) % 3] = -0.0f;
    rays.push_back(ray);
  }
  return rays;
}

TEST(ReferenceTraversal, RaysAlongAxesAgreeWithBruteForce) {
  TriangleMesh boxes;  // axis-aligned faces: flat leaf boxes, rays in their planes
  boxes.append(scene::procedural::makeBox({1, 1, 1}, 0), glm::mat4(1.0f), 1);
  boxes.append(scene::procedural::makeBox({0.5f, 2, 0.25f}, 0), glm::translate(glm::mat4(1.0f), {2, 0, 0}), 2);
  boxes.append(scene::procedural::makeBox({0.5f, 0.5f, 0.5f}, 0), glm::translate(glm::mat4(1.0f), {0, 1.5f, 0}), 3);
  expectAgreement(boxes, axisRays(boxes, 6000, 1), 0.3);
  const TriangleMesh flat = grid(24, 2);
  expectAgreement(flat, axisRays(flat, 6000, 2), 0.12);  // two thirds lie in its plane or pass beside it
  const TriangleMesh closed = cubeSphere(8);
  expectAgreement(closed, axisRays(closed, 6000, 3), 0.4);
}

// Rays through the grid's interior vertices and edge points must hit, straight down (exactly
// through them) or from random origins above; the same on a rotated, moved copy of the grid,
// whose vertices are no longer on integers.
TEST(ReferenceTraversal, RaysThroughSharedEdgesAndVerticesOfAGridHit) {
  constexpr uint32_t kCells = 24;
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (bool rotated : {false, true}) {
    TriangleMesh mesh = grid(kCells, rotated ? 5 : 4);
    const glm::mat4 m = rotated ? randomRigidTransform(rng) : glm::mat4(1.0f);
    transform(mesh, m);
    const glm::vec3 up = glm::normalize(glm::vec3(m * glm::vec4(0, 0, 1, 0)));
    std::vector<Ray> rays;
    for (uint32_t y = 1; y < kCells; ++y)
      for (uint32_t x = 1; x < kCells; ++x)
        for (glm::vec2 offset : {glm::vec2(0.0f), glm::vec2(0.5f, 0.0f), glm::vec2(0.0f, 0.5f), glm::vec2(0.5f)}) {
          const glm::vec3 target = glm::vec3(m * glm::vec4(float(x) + offset.x, float(y) + offset.y, 0.0f, 1.0f));
          rays.push_back(Ray{target + up * (1.0f + 4.0f * unit(rng)), -up});
          const glm::vec3 slanted = glm::normalize(up + 0.8f * randomUnitVector(rng) * glm::vec3(1, 1, 0));
          const glm::vec3 origin = target + slanted * (1.0f + 4.0f * unit(rng));
          rays.push_back(Ray{origin, target - origin});
        }
    const Bvh bvh = buildSah(mesh);
    for (size_t i = 0; i < rays.size(); ++i) {
      // The grid is seen from above, so every ray's target is covered unless there is a gap.
      if (glm::dot(rays[i].direction, up) >= -1e-3f) continue;
      ASSERT_NE(bruteForceClosestHit(mesh.view(), rays[i]).triangle, HMB_NO_HIT) << "ray " << i << " rotated " << rotated;
    }
    const Agreement agreement = compareWithBruteForce(bvh, mesh.view(), rays);
    EXPECT_EQ(agreement.mismatches, 0u) << agreement.firstMismatch;
  }
}

// A closed mesh (shared vertices, no seams), rotated: from inside, every ray must hit, aimed at
// any vertex, any edge midpoint or anywhere.
TEST(ReferenceTraversal, ClosedMeshHasNoGapsFromInside) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  TriangleMesh mesh = cubeSphere(12);
  const glm::mat4 m = randomRigidTransform(rng);
  transform(mesh, m);
  const glm::vec3 centre = glm::vec3(m * glm::vec4(0, 0, 0, 1));
  std::vector<glm::vec3> targets = mesh.positions;
  for (size_t t = 0; t < mesh.indices.size(); t += 3)
    for (int e = 0; e < 3; ++e)
      targets.push_back(0.5f * (mesh.positions[mesh.indices[t + e]] + mesh.positions[mesh.indices[t + (e + 1) % 3]]));
  std::vector<Ray> rays;
  for (const glm::vec3& target : targets) {
    const glm::vec3 origin = centre + randomUnitVector(rng) * 0.5f * unit(rng);
    rays.push_back(Ray{origin, target - origin});
    rays.push_back(Ray{centre, randomUnitVector(rng)});
  }
  const Bvh bvh = buildSah(mesh);
  for (size_t i = 0; i < rays.size(); ++i)
    ASSERT_NE(closestHit(bvh, mesh.view(), rays[i]).triangle, HMB_NO_HIT) << "ray " << i << " escaped";
  const Agreement agreement = compareWithBruteForce(bvh, mesh.view(), rays);
  EXPECT_EQ(agreement.mismatches, 0u) << agreement.firstMismatch;
  EXPECT_EQ(agreement.hits, agreement.rays);
}

// Zero-area triangles (a point, a repeated vertex, collinear vertices) and exact duplicates
// (same vertices; same vertices rotated in order) mixed into a soup.
TEST(ReferenceTraversal, DegenerateAndDuplicatedTrianglesAgreeWithBruteForce) {
  std::mt19937 rng(51);
  TriangleMesh mesh = randomSoup(1500, 0.1f, 52);
  const uint32_t original = mesh.triangleCount();
  std::set<uint32_t> degenerate;
  std::uniform_int_distribution<uint32_t> pick(0, original - 1);
  for (int i = 0; i < 300; ++i) {
    const uint32_t t = pick(rng);
    const uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
    if (i % 2) mesh.indices.insert(mesh.indices.end(), {a, b, c});  // the very same triangle
    else mesh.indices.insert(mesh.indices.end(), {b, c, a});        // same, other first vertex
    mesh.objectIds.push_back(mesh.objectIds[t]);
  }
  for (int i = 0; i < 300; ++i) {
    const glm::vec3 p = randomPointIn(mesh.bounds(), rng), q = randomPointIn(mesh.bounds(), rng);
    // Repeated vertices have no area in any projection; collinear ones may keep a sliver of a
    // rounding's width once sheared, so only the former must never be hit.
    if (i % 3 != 2) degenerate.insert(mesh.triangleCount());
    if (i % 3 == 0) mesh.addTriangle(p, p, p, 9);
    else if (i % 3 == 1) mesh.addTriangle(p, q, q, 9);
    else mesh.addTriangle(p, 0.5f * (p + q), q, 9);
  }
  std::vector<Ray> rays = mixedRays(mesh, 4000, 53);
  for (int i = 0; i < 2000; ++i) {  // aimed at duplicated and degenerate triangles
    const uint32_t t = original + static_cast<uint32_t>(i) % (mesh.triangleCount() - original);
    const glm::vec3 target = randomPointOnTriangle(mesh.view(), t, rng);
    const glm::vec3 origin = target + randomUnitVector(rng) * 2.0f;
    rays.push_back(Ray{origin, target - origin});
  }
  expectAgreement(mesh, rays, 0.4);
  for (const Ray& ray : rays) {
    const Hit hit = bruteForceClosestHit(mesh.view(), ray);
    ASSERT_EQ(degenerate.count(hit.triangle), 0u) << "a zero-area triangle was hit";
    // An exact duplicate ties with its original at the same t: the lower id wins.
    if (hit.triangle >= original && hit.triangle < original + 300 && (hit.triangle - original) % 2 == 1)
      ADD_FAILURE() << "duplicate " << hit.triangle << " won over its lower-id original";
  }
}

// Sheets at z = 0, 1, 2, 3, one object each, seen from above: ignoring the object first hit
// finds the sheet behind it, both through the BVH and by brute force.
TEST(ReferenceTraversal, IgnoredObjectIsSeenThrough) {
  TriangleMesh sheets;
  for (uint32_t layer = 0; layer < 4; ++layer)
    sheets.append(scene::procedural::makePlane({8, 8}, 0),
                  glm::rotate(glm::translate(glm::mat4(1.0f), {0, 0, float(layer)}), 1.5707964f, {1, 0, 0}),
                  10 + layer);
  const Bvh bvh = buildSah(sheets);
  std::mt19937 rng(61);
  std::uniform_real_distribution<float> across(-3.0f, 3.0f);
  for (int i = 0; i < 500; ++i) {
    const Ray ray{{across(rng), across(rng), 10.0f}, {0.02f * across(rng), 0.02f * across(rng), -1.0f}};
    const Hit top = closestHit(bvh, sheets.view(), ray);
    ASSERT_EQ(top.objectId, 13u);
    const Hit behind = closestHit(bvh, sheets.view(), ray, TraceOptions{13});
    ASSERT_EQ(behind.objectId, 12u);
    EXPECT_GT(behind.t, top.t);
  }
  // Random soups with seven objects interleaved in space: ignore what is hit first.
  const TriangleMesh soup = randomSoup(3000, 0.1f, 62);
  const Bvh soupBvh = buildSah(soup);
  const std::vector<Ray> rays = mixedRays(soup, 4000, 63);
  uint32_t seenThrough = 0, mismatches = 0;
  for (const Ray& ray : rays) {
    const Hit first = bruteForceClosestHit(soup.view(), ray);
    if (first.triangle == HMB_NO_HIT) continue;
    const TraceOptions ignore{first.objectId};
    const Hit expected = bruteForceClosestHit(soup.view(), ray, ignore);
    const Hit actual = closestHit(soupBvh, soup.view(), ray, ignore);
    ASSERT_NE(expected.objectId, first.objectId);
    if (expected.triangle != HMB_NO_HIT) {
      ++seenThrough;
      EXPECT_GE(expected.t, first.t);
    }
    if (expected.triangle != actual.triangle || expected.t != actual.t) ++mismatches;
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_GT(seenThrough, 500u);
}

TEST(ReferenceTraversal, EmptyAndSingleTriangleMeshes) {
  const TriangleMesh empty;
  const Bvh emptyBvh = buildSah(empty);
  const Ray ray{{0.2f, 0.2f, 1.0f}, {0, 0, -1}};
  EXPECT_EQ(closestHit(emptyBvh, empty.view(), ray).triangle, HMB_NO_HIT);
  EXPECT_EQ(bruteForceClosestHit(empty.view(), ray).triangle, HMB_NO_HIT);
  TriangleMesh one;
  one.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 5);
  const Hit hit = closestHit(buildSah(one), one.view(), ray);
  EXPECT_EQ(hit.triangle, 0u);
  EXPECT_EQ(hit.objectId, 5u);
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  expectAgreement(one, mixedRays(one, 2000, 71), 0.3);
}

TEST(ReferenceTraversal, RayIntervalAndInvalidRays) {
  TriangleMesh one;
  one.addTriangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
  const Bvh bvh = buildSah(one);
  EXPECT_EQ(closestHit(bvh, one.view(), Ray{{0.2f, 0.2f, 1.0f}, {0, 0, -1}, 0.0f, 0.5f}).triangle, HMB_NO_HIT);
  EXPECT_EQ(closestHit(bvh, one.view(), Ray{{0.2f, 0.2f, 1.0f}, {0, 0, -1}, 1.5f, kInf}).triangle, HMB_NO_HIT);
  EXPECT_EQ(closestHit(bvh, one.view(), Ray{{0.2f, 0.2f, 1.0f}, {0, 0, -1}, 1.0f, 1.0f}).triangle, 0u);
  EXPECT_EQ(closestHit(bvh, one.view(), Ray{{0.2f, 0.2f, 1.0f}, {0, 0, 0}}).triangle, HMB_NO_HIT);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(closestHit(bvh, one.view(), Ray{{0.2f, 0.2f, 1.0f}, {0, nan, -1}}).triangle, HMB_NO_HIT);
}

}  // namespace
}  // namespace hmb::bvh::test
