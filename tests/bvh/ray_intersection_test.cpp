// The ray-box and ray-triangle tests on their own: rays along axes and in slab planes (1/0 and
// 0 * inf), degenerate triangles, and watertightness at shared edges and vertices.
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "bvh/ray_intersection.h"
#include "tests/bvh/bvh_test_support.h"

namespace hmb::bvh::test {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
const Aabb kUnitBox{{0, 0, 0}, {1, 1, 1}};

bool boxHit(const Ray& ray, const Aabb& box, float& tNear) {
  return intersectBox(PreparedRay(ray), box, ray.tMin, ray.tMax, tNear);
}

TEST(RayBox, HitsFromOutsideAndInsideAndRespectsTheInterval) {
  float tNear = -1.0f;
  EXPECT_TRUE(boxHit(Ray{{-1, 0.5f, 0.5f}, {1, 0, 0}}, kUnitBox, tNear));
  EXPECT_FLOAT_EQ(tNear, 1.0f);
  EXPECT_TRUE(boxHit(Ray{{0.5f, 0.5f, 0.5f}, {0.3f, -0.2f, 0.9f}}, kUnitBox, tNear));
  EXPECT_FLOAT_EQ(tNear, 0.0f);  // inside: the interval starts at tMin
  EXPECT_FALSE(boxHit(Ray{{2, 0.5f, 0.5f}, {1, 0, 0}}, kUnitBox, tNear));         // behind the origin
  EXPECT_FALSE(boxHit(Ray{{-1, 0.5f, 0.5f}, {1, 0, 0}, 0.0f, 0.5f}, kUnitBox, tNear));  // beyond tMax
  EXPECT_FALSE(boxHit(Ray{{-1, 0.5f, 0.5f}, {1, 0, 0}, 2.5f, kInf}, kUnitBox, tNear));  // before tMin
  EXPECT_FALSE(boxHit(Ray{{-1, 2.0f, 0.5f}, {1, 0, 0}}, kUnitBox, tNear));
}

// A ray along one axis whose other coordinates lie exactly on the box's faces: 0 * inf in those
// slabs must not turn into NaN or a miss, for +0 and -0 direction components alike.
TEST(RayBox, AxisRaysInFacePlanesCountAsInside) {
  for (int along = 0; along < 3; ++along)
    for (float sign : {1.0f, -1.0f})
      for (float zero : {0.0f, -0.0f})
        for (float onFace : {0.0f, 1.0f}) {
          Ray ray;
          ray.direction = glm::vec3(zero);
          ray.direction[along] = sign;
          ray.origin = glm::vec3(onFace);
          ray.origin[along] = sign > 0 ? -3.0f : 4.0f;
          float tNear = -1.0f;
          ASSERT_TRUE(boxHit(ray, kUnitBox, tNear)) << "axis " << along << " sign " << sign << " face " << onFace;
          EXPECT_FLOAT_EQ(tNear, 3.0f);
          ray.origin[(along + 1) % 3] = onFace == 0.0f ? -0.001f : 1.001f;  // just outside that face
          EXPECT_FALSE(boxHit(ray, kUnitBox, tNear));
        }
}

TEST(RayBox, FlatBoxesHitWhenCrossedOrLyingInTheirPlane) {
  const Aabb flat{{0, 0, 0.5f}, {1, 1, 0.5f}};
  float tNear = -1.0f;
  EXPECT_TRUE(boxHit(Ray{{0.25f, 0.75f, 2.0f}, {0, 0, -1}}, flat, tNear));
  EXPECT_FLOAT_EQ(tNear, 1.5f);
  EXPECT_TRUE(boxHit(Ray{{-1.0f, 0.5f, 0.5f}, {1, 0, 0}}, flat, tNear));  // in the plane: 0 * inf in z
  EXPECT_FLOAT_EQ(tNear, 1.0f);
  EXPECT_FALSE(boxHit(Ray{{-1.0f, 0.5f, 0.5001f}, {1, 0, 0}}, flat, tNear));
  const Aabb point{{0.5f, 0.5f, 0.5f}, {0.5f, 0.5f, 0.5f}};
  EXPECT_TRUE(boxHit(Ray{{0.5f, 0.5f, -2.0f}, {0, 0, 1}}, point, tNear));
  EXPECT_FLOAT_EQ(tNear, 2.5f);
}

bool triangleHit(const Ray& ray, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, TriangleHit& hit) {
  return intersectTriangle(PreparedRay(ray), a, b, c, hit);
}

TEST(RayTriangle, HitGivesDistanceAndBarycentricsFromBothSides) {
  const glm::vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  TriangleHit hit;
  ASSERT_TRUE(triangleHit(Ray{{0.5f, 0.25f, 3.0f}, {0, 0, -2}}, a, b, c, hit));
  EXPECT_FLOAT_EQ(hit.t, 1.5f);
  EXPECT_FLOAT_EQ(hit.u, 0.25f);
  EXPECT_FLOAT_EQ(hit.v, 0.125f);
  ASSERT_TRUE(triangleHit(Ray{{0.5f, 0.25f, -3.0f}, {0, 0, 1}}, a, b, c, hit));  // back side
  EXPECT_FLOAT_EQ(hit.t, 3.0f);
  EXPECT_FLOAT_EQ(hit.u, 0.25f);
  EXPECT_FALSE(triangleHit(Ray{{1.5f, 1.5f, 3.0f}, {0, 0, -1}}, a, b, c, hit));
}

TEST(RayTriangle, HitPointMatchesBarycentricsOnRandomRays) {
  std::mt19937 rng(5);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 a = randomUnitVector(rng), b = randomUnitVector(rng), c = randomUnitVector(rng);
    // Aimed near the triangle's centre, so that about half of the rays hit.
    const glm::vec3 origin = randomUnitVector(rng) * 3.0f;
    const Ray ray{origin, (a + b + c) / 3.0f + 0.3f * randomUnitVector(rng) - origin};
    TriangleHit hit;
    if (!triangleHit(ray, a, b, c, hit)) continue;
    ++hits;
    ASSERT_GE(hit.u, 0.0f);
    ASSERT_GE(hit.v, 0.0f);
    ASSERT_LE(hit.u + hit.v, 1.0f + 1e-6f);
    const glm::vec3 onRay = ray.origin + hit.t * ray.direction;
    const glm::vec3 onTriangle = (1.0f - hit.u - hit.v) * a + hit.u * b + hit.v * c;
    ASSERT_LT(glm::length(onRay - onTriangle), 1e-4f) << "ray " << i;
  }
  EXPECT_GT(hits, 5000);
}

TEST(RayTriangle, DegenerateTrianglesAndRaysInThePlaneMiss) {
  const Ray down{{0.3f, 0.3f, 1.0f}, {0, 0, -1}};
  TriangleHit hit;
  EXPECT_FALSE(triangleHit(down, {0, 0, 0}, {1, 1, 0}, {2, 2, 0}, hit));  // collinear, the ray on its line
  EXPECT_FALSE(triangleHit(down, {0.3f, 0.3f, 0}, {0.3f, 0.3f, 0}, {0.3f, 0.3f, 0}, hit));  // a point
  EXPECT_FALSE(triangleHit(down, {0, 0, 0}, {1, 0, 0}, {1, 0, 0}, hit));  // repeated vertex
  // In the triangle's own plane: no area seen, no hit (its neighbours' boxes still see it).
  EXPECT_FALSE(triangleHit(Ray{{-1.0f, 0.2f, 0.0f}, {1, 0, 0}}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, hit));
}

// The ray passes e^2-close to the shared edge BC (e = 2^-23), on A's side: in float both
// products of the edge function round to the same value, so it is exactly 0 and only the
// double recomputation tells which of the two neighbours is hit (without it, both are).
TEST(RayTriangle, EdgeFunctionRoundedToZeroIsDecidedExactly) {
  const float e = std::ldexp(1.0f, -23);
  // Coordinates in the ray's sheared plane; looking down -z from above the origin, the shear
  // maps world (x, y) to (y, x).
  const glm::vec2 a(-1.0f, 1.0f), b(-1.0f, -(1.0f + e)), c(1.0f + e, 1.0f + 2.0f * e), d(1.0f, -1.0f);
  const auto world = [](glm::vec2 s) { return glm::vec3(s.y, s.x, 0.0f); };
  const double exactProducts = double{c.x} * b.y - double{c.y} * b.x;
  ASSERT_NE(exactProducts, 0.0);
  const auto side = [&](glm::vec2 p) {  // orientation of (b, c, p), exact in double
    return (double{c.x} - b.x) * (double{p.y} - b.y) - (double{c.y} - b.y) * (double{p.x} - b.x);
  };
  ASSERT_GT(side(glm::vec2(0.0f)) * side(a), 0.0) << "the origin is on A's side";
  ASSERT_LT(side(glm::vec2(0.0f)) * side(d), 0.0);
  const Ray down{{0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}};
  TriangleHit hit;
  EXPECT_TRUE(triangleHit(down, world(a), world(b), world(c), hit));
  EXPECT_FALSE(triangleHit(down, world(d), world(c), world(b), hit));
}

// Two triangles sharing an edge, arbitrary float vertices, seen so that they lie on opposite
// sides of the edge: a ray aimed at a point of the edge passes within rounding of it, where
// only a gap between the two could let it through.
TEST(RayTriangle, SharedEdgesLeaveNoGap) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int rays = 0;
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 p = randomUnitVector(rng), q = randomUnitVector(rng);
    const glm::vec3 mid = 0.5f * (p + q), across = glm::normalize(glm::cross(q - p, randomUnitVector(rng)));
    const glm::vec3 left = mid + across + 0.3f * randomUnitVector(rng);
    const glm::vec3 right = mid - across + 0.3f * randomUnitVector(rng);
    for (int k = 0; k < 4; ++k) {
      const glm::vec3 target = p + (k == 0 ? 0.5f : unit(rng)) * (q - p);
      Ray ray{target + 4.0f * randomUnitVector(rng), {}};
      ray.direction = target - ray.origin;
      // Opposite sides in projection: (p, q, left) and (p, q, right) turn opposite ways.
      const float sideLeft = glm::dot(ray.direction, glm::cross(q - p, left - p));
      const float sideRight = glm::dot(ray.direction, glm::cross(q - p, right - p));
      if (!(sideLeft * sideRight < 0.0f)) continue;
      ++rays;
      const PreparedRay prepared(ray);
      TriangleHit hit;
      // The neighbour with either winding and either starting vertex, as meshes have any.
      const bool hitsLeft = intersectTriangle(prepared, p, q, left, hit);
      const bool hitsRight = (i % 2) ? intersectTriangle(prepared, q, p, right, hit)
                                     : intersectTriangle(prepared, right, p, q, hit);
      ASSERT_TRUE(hitsLeft || hitsRight) << "pair " << i << " edge point " << k;
    }
  }
  EXPECT_GT(rays, 5000);
}

// A fan of triangles around a shared vertex, seen so that it covers the vertex in projection:
// a ray aimed at the vertex must hit one of them.
TEST(RayTriangle, SharedVerticesLeaveNoGap) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int rays = 0;
  for (int i = 0; i < 5000; ++i) {
    const glm::vec3 centre = randomUnitVector(rng) * unit(rng);
    const int sides = 3 + i % 7;
    std::vector<glm::vec3> ring;
    for (int k = 0; k < sides; ++k) {
      const float angle = 6.2831853f * (k + 0.8f * unit(rng)) / sides;
      ring.push_back(centre + glm::vec3(std::cos(angle), std::sin(angle), 0.6f * (unit(rng) - 0.5f)) *
                                  (0.2f + unit(rng)));
    }
    const glm::vec3 target = centre;
    Ray ray{target + 3.0f * randomUnitVector(rng), {}};
    ray.direction = target - ray.origin;
    bool covers = true;  // every triangle turns the same way in projection
    for (int k = 0; k < sides; ++k) {
      const glm::vec3 a = ring[k], b = ring[(k + 1) % sides];
      covers = covers && glm::dot(ray.direction, glm::cross(a - centre, b - centre)) < 0.0f;
    }
    if (!covers) continue;
    ++rays;
    const PreparedRay prepared(ray);
    bool hitAny = false;
    for (int k = 0; k < sides; ++k) {
      const glm::vec3 a = ring[k], b = ring[(k + 1) % sides];
      TriangleHit hit;
      // Varying which corner comes first and the winding, as meshes do.
      hitAny = hitAny || ((k + i) % 3 == 0   ? intersectTriangle(prepared, centre, a, b, hit)
                          : (k + i) % 3 == 1 ? intersectTriangle(prepared, b, centre, a, hit)
                                             : intersectTriangle(prepared, a, centre, b, hit));
    }
    ASSERT_TRUE(hitAny) << "fan " << i;
  }
  EXPECT_GT(rays, 1000);
}

}  // namespace
}  // namespace hmb::bvh::test
