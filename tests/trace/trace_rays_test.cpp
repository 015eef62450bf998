// The trace kernel against brute force over every triangle: single meshes with adversarial rays
// (along axes, grazing, through shared vertices and edges, degenerate and coincident
// triangles), and a two-level scene with rotating instances traced at several shutter times,
// with and without an ignored object. Also: the top level's motion bounds hold every instance
// at every shutter time.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <random>
#include <sstream>
#include <string>

#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "bvh/reference_traversal.h"
#include "hmblur/load_scene.h"
#include "runtime/vulkan/frame_recorder.h"
#include "scenes/assimp_test_models.h"
#include "tests/support/vulkan_test.h"
#include "tests/trace/trace_harness.h"

namespace hmb::trace::test {
namespace {

using bvh::Ray;
using bvh::test::TriangleMesh;

bool near(float a, float b, float tolerance) {
  return std::abs(a - b) <= tolerance * std::max({std::abs(a), std::abs(b), 1.0f});
}

// The device and the host agree when both miss, or both hit at the same t (within the float
// rounding of different instruction orders). The triangle must match too, unless another
// triangle is hit at that same t (a shared edge or vertex, or coincident triangles).
struct Comparison {
  uint32_t rays = 0, hits = 0, mismatches = 0;
  std::string firstMismatch;
  void add(size_t ray, const gpu::BvhHit& expected, const gpu::BvhHit& actual, uint32_t expectedInstance,
           float tolerance) {
    ++rays;
    if (expected.triangle != HMB_NO_HIT) ++hits;
    bool agree;
    if (expected.triangle == HMB_NO_HIT || actual.triangle == HMB_NO_HIT)
      agree = expected.triangle == actual.triangle;
    else
      agree = near(expected.t, actual.t, tolerance) &&
              ((actual.triangle == expected.triangle && actual.instance == expectedInstance &&
                near(expected.u, actual.u, 1e-3f) && near(expected.v, actual.v, 1e-3f)) ||
               actual.triangle != expected.triangle || actual.instance != expectedInstance);
    if (agree) return;
    if (mismatches++ == 0) {
      std::ostringstream s;
      s << "ray " << ray << ": host triangle " << expected.triangle << " (instance " << expectedInstance << ") t "
        << expected.t << ", device triangle " << actual.triangle << " (instance " << actual.instance << ") t "
        << actual.t;
      firstMismatch = s.str();
    }
  }
};

class TraceRays : public hmb::test::VulkanTest {
 protected:
  // Traces `rays` through `mesh` as a one-instance scene and compares with brute force.
  Comparison compareOnMesh(const TriangleMesh& mesh, std::span<const Ray> rays) {
    const std::vector<gpu::BvhHit> hits = traceMesh(context(), mesh, rays);
    Comparison comparison;
    TriangleMesh oneObject = mesh;  // the scene gives the whole mesh object id 1
    oneObject.objectIds.assign(mesh.triangleCount(), 1u);
    for (size_t i = 0; i < rays.size(); ++i) {
      gpu::BvhHit expected = bvh::bruteForceClosestHit(oneObject.view(), rays[i]);
      comparison.add(i, expected, hits[i], 0u, 1e-5f);
    }
    return comparison;
  }
};

std::vector<Ray> axisRays(const TriangleMesh& mesh, uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  const Aabb box = mesh.bounds();
  std::vector<Ray> rays;
  for (uint32_t i = 0; i < count; ++i) {
    Ray ray;
    glm::vec3 d(0.0f);
    d[i % 3] = (i / 3) % 2 ? 1.0f : -1.0f;
    ray.direction = d;
    ray.origin = bvh::test::randomPointIn(box, rng);
    ray.origin[i % 3] = d[i % 3] > 0 ? box.min[i % 3] - 1.0f : box.max[i % 3] + 1.0f;
    rays.push_back(ray);
  }
  return rays;
}

// Rays aimed exactly at shared interior vertices and edge midpoints of the grid (z = 0 plane).
std::vector<Ray> vertexAndEdgeRays(uint32_t cells, uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<uint32_t> cell(1, cells - 1);
  std::vector<Ray> rays;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 target(float(cell(rng)) + (i % 3 == 1 ? 0.5f : 0.0f), float(cell(rng)) + (i % 3 == 2 ? 0.5f : 0.0f),
                           0.0f);
    const glm::vec3 origin = target + glm::vec3(0.37f * float(i % 5) - 0.7f, 0.21f * float(i % 7) - 0.6f, 3.0f);
    rays.push_back(Ray{origin, target - origin});
  }
  return rays;
}

TEST_F(TraceRays, RandomSoupMatchesBruteForce) {
  const TriangleMesh mesh = bvh::test::randomSoup(3000, 0.08f, 11);
  const std::vector<Ray> rays = bvh::test::mixedRays(mesh, 4000, 12);
  const Comparison c = compareOnMesh(mesh, rays);
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
  EXPECT_GE(c.hits, 1500u);
}

// A scene of one instance is traced without a top level (HMB_SPEC_TRACE_TOP_LEVEL): its hits
// equal the full two-level walk's bit for bit, on mixed rays, rays along the axes, rays with a
// short range, and rays that ignore the instance's object (which must then miss).
TEST_F(TraceRays, OneInstanceScenesTraceTheSameWithoutTheTopLevel) {
  const TriangleMesh mesh = bvh::test::randomSoup(2000, 0.1f, 21);
  const scene::Scene scene = sceneOf(mesh);
  ASSERT_EQ(scene.instances.size(), 1u);
  vk::FrameRecorder frame(context());
  TraceScene traceScene(context(), scene, frame);
  const float time = 0.0f;
  traceScene.setShutterTimes(scene, std::span(&time, 1), frame);
  std::vector<Ray> rays = bvh::test::mixedRays(mesh, 3000, 22);
  const std::vector<Ray> alongAxes = axisRays(mesh, 300, 23);
  rays.insert(rays.end(), alongAxes.begin(), alongAxes.end());
  std::vector<gpu::TraceRay> traceRays;
  for (size_t i = 0; i < rays.size(); ++i) {
    Ray ray = rays[i];
    if (i % 7 == 3) ray.tMax = 0.5f;
    traceRays.push_back(traceRay(ray, 0, i % 5 == 4 ? 1u : HMB_IGNORE_NONE));  // object 1: the mesh
  }
  using TopLevel = passes::TraceRaysPass::TopLevel;
  const std::vector<gpu::BvhHit> direct = traceOnDevice(context(), traceScene, traceRays, 0, TopLevel::WhereNeeded);
  const std::vector<gpu::BvhHit> walked = traceOnDevice(context(), traceScene, traceRays, 0, TopLevel::Always);
  uint32_t hits = 0;
  for (size_t i = 0; i < traceRays.size(); ++i) {
    ASSERT_EQ(std::memcmp(&direct[i], &walked[i], sizeof(gpu::BvhHit)), 0)
        << "ray " << i << ": triangle " << direct[i].triangle << " at " << direct[i].t << " without the top level, "
        << walked[i].triangle << " at " << walked[i].t << " with it";
    if (traceRays[i].ignoreObjectId == 1u) {
      EXPECT_EQ(direct[i].triangle, HMB_NO_HIT) << "ray " << i;
    }
    hits += direct[i].triangle != HMB_NO_HIT;
  }
  EXPECT_GE(hits, 1000u);
}

// The trace meets each packed box through its tree's ray constants (t = q a + c per plane),
// widened by the roundings of those constants and of the stored bounds. Far from the origin the
// bounds' rounding dominates, and rays that start a hair from a triangle see the tightest
// boxes: every such ray must still find what brute force finds.
TEST_F(TraceRays, RaysStartingNextToTrianglesFarFromTheOriginMatchBruteForce) {
  // 4 units of soup 400,000 units out: a float there is 1/32 apart, a tree's step 1/16,000.
  TriangleMesh mesh = bvh::test::randomSoup(1500, 0.3f, 21);
  const glm::vec3 offset(400000.0f, -300000.0f, 450000.0f);
  for (glm::vec3& p : mesh.positions) p = p * 4.0f + offset;
  std::mt19937 rng(22);
  std::uniform_int_distribution<uint32_t> pick(0, mesh.triangleCount() - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  std::vector<Ray> rays;
  for (uint32_t i = 0; i < 4000; ++i) {
    const uint32_t t = pick(rng);
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]], b = mesh.positions[mesh.indices[3 * t + 1]],
                    c = mesh.positions[mesh.indices[3 * t + 2]];
    float u = unit(rng), v = unit(rng);
    if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
    const glm::vec3 point = a + u * (b - a) + v * (c - a);
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    const float side = i % 2 ? 1.0f : -1.0f, gap = 0.1f * float(1 + i % 7);
    const glm::vec3 origin = point + side * gap * normal;
    // Back at the triangle, along it, or away into the soup.
    const glm::vec3 jitter(unit(rng) - 0.5f, unit(rng) - 0.5f, unit(rng) - 0.5f);
    const glm::vec3 direction = i % 3 == 0 ? -side * normal + 0.05f * jitter
                                : i % 3 == 1 ? glm::cross(normal, jitter) + 1e-3f * normal
                                             : jitter;
    rays.push_back(Ray{origin, direction});
  }
  const Comparison c = compareOnMesh(mesh, rays);
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
  EXPECT_GE(c.hits, 1300u);
}

TEST_F(TraceRays, AxisAlignedRaysMatchBruteForce) {
  const TriangleMesh mesh = bvh::test::cubeSphere(12);
  const Comparison c = compareOnMesh(mesh, axisRays(mesh, 3000, 13));
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
  EXPECT_GE(c.hits, 1000u);
}

TEST_F(TraceRays, RaysThroughSharedVerticesAndEdgesNeverLeakThrough) {
  const uint32_t cells = 24;
  const TriangleMesh mesh = bvh::test::grid(cells, 14);
  const Comparison c = compareOnMesh(mesh, vertexAndEdgeRays(cells, 3000, 15));
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
  EXPECT_EQ(c.hits, c.rays);  // every ray aims at a point of the closed grid
}

TEST_F(TraceRays, GrazingRaysInTheMeshPlaneMatchBruteForce) {
  const TriangleMesh mesh = bvh::test::grid(16, 16);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> along(-1.0f, 17.0f);
  std::vector<Ray> rays;
  for (int i = 0; i < 1000; ++i) {
    const float z = i % 2 ? 0.0f : 1e-6f * float(i % 5);  // in the plane, or just above it
    rays.push_back(Ray{glm::vec3(-1.0f, along(rng), z), glm::vec3(1.0f, along(rng) * 0.01f, -z)});
  }
  const Comparison c = compareOnMesh(mesh, rays);
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
}

// Zero-area triangles (points, segments) are not surfaces: where rounding lets either side hit
// one, it may, but only in front of the real surface. Coincident copies tie on t.
TEST_F(TraceRays, DegenerateAndCoincidentTrianglesMatchBruteForce) {
  TriangleMesh mesh = bvh::test::randomSoup(500, 0.1f, 18);
  for (int i = 0; i < 20; ++i) mesh.addTriangle({0.2f, 0.2f, 0.5f}, {0.8f, 0.2f, 0.5f}, {0.2f, 0.8f, 0.5f}, 1);
  mesh.objectIds.assign(mesh.triangleCount(), 1u);  // surfaces are object 1, degenerate ones 2
  const uint32_t firstDegenerate = mesh.triangleCount();
  for (int i = 0; i < 50; ++i) {
    const float x = 0.02f * float(i);
    mesh.addTriangle({x, 0.5f, 0.5f}, {x, 0.5f, 0.5f}, {x, 0.5f, 0.5f}, 2);                // a point
    mesh.addTriangle({x, 0.1f, 0.5f}, {x + 0.1f, 0.1f, 0.5f}, {x + 0.2f, 0.1f, 0.5f}, 2);  // a segment
  }
  const std::vector<Ray> rays = bvh::test::mixedRays(mesh, 3000, 19);
  const std::vector<gpu::BvhHit> hits = traceMesh(context(), mesh, rays);
  Comparison c;
  bvh::TraceOptions surfacesOnly;
  surfacesOnly.ignoreObjectId = 2;
  for (size_t i = 0; i < rays.size(); ++i) {
    const gpu::BvhHit expected = bvh::bruteForceClosestHit(mesh.view(), rays[i], surfacesOnly);
    if (hits[i].triangle != HMB_NO_HIT && hits[i].triangle >= firstDegenerate) {
      EXPECT_LE(hits[i].t, expected.t * (1.0f + 1e-5f)) << "ray " << i << " hit a degenerate triangle behind a surface";
      continue;
    }
    c.add(i, expected, hits[i], 0u, 1e-5f);
  }
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
  EXPECT_GE(c.hits, 1000u);
}

// A real CAD asset in millimetres (Debian assimp-testmodels' 2CylinderEngine, 110k triangles),
// whose long thin triangles (a millimetre wide, 230 long) were hit at up to 1e-3 relative from
// the exact distance when t came from the watertight test's edge functions. Rays aimed at such
// needles from a few millimetres away, and at any triangle from up to 40: each device hit must
// be at the exact nearest t (double precision, brute force) to 1e-4 relative, as the bvh suite
// demands against Embree, except where the ray grazes an edge nearer than its hit (float tests
// may rightly pick another triangle there).
TEST_F(TraceRays, CadAssetHitsAreAtTheExactDistance) {
  const std::filesystem::path models = scene::assimpGltfModels();
  const std::filesystem::path asset = models / "2CylinderEngine-glTF-Binary" / "2CylinderEngine.glb";
  if (models.empty() || !std::filesystem::exists(asset)) GTEST_SKIP() << "assimp-testmodels is not installed";
  const scene::Scene scene = scene::loadScene(asset.string());
  const TriangleMesh mesh = bvh::test::sceneTriangles(scene, scene.settings.frameTime);
  std::vector<uint32_t> needles;  // longest edge at least 50 times the height on it
  for (uint32_t t = 0; t < mesh.triangleCount(); ++t) {
    const auto [p0, p1, p2] = mesh.view().vertices(t);
    const float longest = std::max({glm::length(p1 - p0), glm::length(p2 - p1), glm::length(p0 - p2)});
    const float doubleArea = glm::length(glm::cross(p1 - p0, p2 - p0));
    if (doubleArea > 0.0f && longest * longest >= 50.0f * doubleArea) needles.push_back(t);
  }
  ASSERT_GE(needles.size(), 100u);
  std::mt19937 rng(77);
  std::uniform_int_distribution<uint32_t> anyTriangle(0, mesh.triangleCount() - 1);
  std::uniform_int_distribution<size_t> anyNeedle(0, needles.size() - 1);
  std::uniform_real_distribution<float> near(0.5f, 10.0f), far(2.0f, 40.0f);
  std::vector<Ray> rays;
  for (int i = 0; i < 1500; ++i) {
    const bool needle = i % 2 == 0;
    const uint32_t triangle = needle ? needles[anyNeedle(rng)] : anyTriangle(rng);
    const glm::vec3 target = bvh::test::randomPointOnTriangle(mesh.view(), triangle, rng);
    const glm::vec3 direction = bvh::test::randomUnitVector(rng);
    rays.push_back(Ray{target - direction * (needle ? near(rng) : far(rng)), direction});
  }
  const std::vector<gpu::BvhHit> hits = traceMesh(context(), mesh, rays);
  uint32_t checked = 0, wrong = 0;
  std::string first;
  for (size_t i = 0; i < rays.size(); ++i) {
    const bvh::ExactHit exact = bvh::exactClosestHit(mesh.view(), rays[i]);
    const bool deviceHit = hits[i].triangle != HMB_NO_HIT;
    const double deviceT = deviceHit ? double(hits[i].t) : INFINITY;
    if (exact.grazeT <= std::min(deviceT, exact.t) * (1.0 + 1e-4)) continue;
    ++checked;
    const bool right = deviceHit == std::isfinite(exact.t) &&
                       (!deviceHit || std::abs(deviceT - exact.t) <= 1e-4 * std::max(1.0, exact.t));
    if (right) continue;
    if (wrong++ == 0)
      first = "ray " + std::to_string(i) + ": device t " + std::to_string(deviceT) + ", exact " + std::to_string(exact.t);
  }
  EXPECT_EQ(wrong, 0u) << first;
  EXPECT_GE(checked, 1400u);
}

TEST_F(TraceRays, InvalidRaysMissAndFiniteRangesAreRespected) {
  const TriangleMesh mesh = bvh::test::cubeSphere(8);
  const float nan = std::nanf(""), inf = std::numeric_limits<float>::infinity();
  const std::vector<Ray> rays = {
      Ray{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f)},                              // zero direction
      Ray{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(nan, 0.0f, -1.0f)},                  // NaN direction
      Ray{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f, inf, -1.0f)},                  // infinite direction
      Ray{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f, 0.0f, -1.0f), 0.0f, 3.0f},     // ends before the sphere
      Ray{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f, 0.0f, -1.0f), 4.5f, inf},      // starts inside it
      Ray{glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, -1e-30f)},               // tiny direction
      Ray{glm::vec3(0.0f, 0.0f, 5.0f), glm::vec3(0.0f, 0.0f, -1e30f)},                // huge direction
  };
  const Comparison c = compareOnMesh(mesh, rays);
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
}

// Back faces of single-sided instances are skipped when asked (as the rasterizer culls them),
// also under a transform that flips handedness; double-sided ones are always hit.
TEST_F(TraceRays, BackFacesOfSingleSidedInstancesAreCulledOnRequest) {
  scene::Scene scene;
  scene::Mesh quad;  // counter-clockwise seen from +z: its front faces +z
  quad.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  quad.material = 0;
  scene.meshes = {quad, quad};
  scene.meshes[1].material = 1;
  scene.materials = {scene::Material{}, scene::Material{}};
  scene.materials[1].doubleSided = true;
  // Single-sided at z = 0; single-sided and mirrored (scale z = -1) at z = -2; double-sided at
  // z = -4. The mirror leaves the quad's points in place but makes its object-space winding
  // clockwise (glTF: a negative determinant flips the winding), so its world front is +z too.
  scene::Node plain, mirrored, doubleSided;
  mirrored.local.translation = {0, 0, -2};
  mirrored.local.scale = {1, 1, -1};
  doubleSided.local.translation = {0, 0, -4};
  scene.nodes = {plain, mirrored, doubleSided};
  scene.instances = {{0, 0, 1}, {0, 1, 2}, {1, 2, 3}};
  vk::FrameRecorder frame(context());
  TraceScene traceScene(context(), scene, frame);
  const float time = 0.0f;
  traceScene.setShutterTimes(scene, std::span(&time, 1), frame);
  const auto hitObject = [&](glm::vec3 origin, glm::vec3 direction, uint32_t flags) {
    const std::vector<gpu::TraceRay> ray = {traceRay({origin, direction, 0.0f, 100.0f})};
    return traceOnDevice(context(), traceScene, ray, flags)[0].objectId;
  };
  const glm::vec3 down(0, 0, -1), up(0, 0, 1);
  // Fronts are hit either way.
  EXPECT_EQ(hitObject({0.1f, 0.2f, 5.0f}, down, HMB_TRACE_CULL_BACK_FACES), 1u);
  EXPECT_EQ(hitObject({0.1f, 0.2f, -1.0f}, down, HMB_TRACE_CULL_BACK_FACES), 2u);
  // Backs: hit without culling, passed through with it.
  EXPECT_EQ(hitObject({0.1f, 0.2f, -1.0f}, up, 0u), 1u);
  EXPECT_EQ(hitObject({0.1f, 0.2f, -1.0f}, up, HMB_TRACE_CULL_BACK_FACES), HMB_NO_HIT);
  EXPECT_EQ(hitObject({0.1f, 0.2f, -3.0f}, up, 0u), 2u);
  EXPECT_EQ(hitObject({0.1f, 0.2f, -3.0f}, up, HMB_TRACE_CULL_BACK_FACES), HMB_NO_HIT);
  // The double-sided quad's back is never culled.
  EXPECT_EQ(hitObject({0.1f, 0.2f, -9.0f}, up, HMB_TRACE_CULL_BACK_FACES), 3u);
}

// A ray through the boxes of 20,000 instances, missing every one's triangle, to a wall behind
// them: Mesa 22.3's lavapipe ends every loop of an invocation after 65535 rounds in all, and
// the walk with them. The trace is then flagged and counted (closest_hit.glsl), never a silent
// miss; a driver without the limit finds the wall. A ray beside the instances, alone, is never
// cut: it runs along their row, and the walk culls boxes on the axes a ray runs across (it once
// walked every box, and was cut too).
TEST_F(TraceRays, AWalkCutShortByTheDriversLoopLimitIsFlaggedAndCounted) {
  const uint32_t slivers = 20000;
  scene::Scene scene;
  scene::Mesh sliver, wall;
  // In the plane y = z, over the unit cube: a ray along x at y = 0.9, z = 0.1 passes through its
  // box and misses it.
  sliver.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
  sliver.indices = {0, 1, 2};
  wall.positions = {{0, -2, -2}, {0, 2, -2}, {0, 2, 2}, {0, -2, 2}};
  wall.indices = {0, 1, 2, 0, 2, 3};
  scene.meshes = {sliver, wall};
  scene.materials = {scene::Material{}};
  scene.materials[0].doubleSided = true;
  for (uint32_t i = 0; i < slivers; ++i) {
    scene::Node node;
    node.local.translation = {float(i), 0, 0};
    scene.nodes.push_back(node);
    scene.instances.push_back({0, i, 1});
  }
  scene::Node end;
  end.local.translation = {float(slivers + 1), 0, 0};
  scene.nodes.push_back(end);
  scene.instances.push_back({1, slivers, 2});
  vk::FrameRecorder frame(context());
  TraceScene traceScene(context(), scene, frame);
  const float time = 0.0f;
  traceScene.setShutterTimes(scene, std::span(&time, 1), frame);
  // The ray through the boxes, and one beside them in the same SIMD batch (the limit is the
  // batch's: cut too, where the other is): each cut or right, and the cut ones counted.
  const gpu::TraceRay through = traceRay({{-1.0f, 0.9f, 0.1f}, {1, 0, 0}, 0.0f, 1e6f});
  const gpu::TraceRay beside = traceRay({{-1.0f, 1.5f, 1.5f}, {1, 0, 0}, 0.0f, 1e6f});
  const std::vector<gpu::BvhHit> hits = traceOnDevice(context(), traceScene, std::vector{through, beside});
  for (const gpu::BvhHit& hit : hits) {
    if (hit.cut != 0u) continue;
    EXPECT_EQ(hit.objectId, 2u) << "an uncut walk finds the wall";
    EXPECT_NEAR(hit.t, float(slivers + 2), 1e-2f);
  }
  std::printf("[ cut      ] the walk through %u boxes was %s\n", slivers, hits[0].cut ? "cut short" : "whole");
  EXPECT_EQ(traceScene.cutTraces(), hits[0].cut + hits[1].cut);
  // Alone, the ray beside them is never cut.
  const gpu::BvhHit alone = traceOnDevice(context(), traceScene, std::vector{beside}).at(0);
  EXPECT_EQ(alone.cut, 0u);
  EXPECT_EQ(alone.objectId, 2u);
  EXPECT_EQ(traceScene.cutTraces(), hits[0].cut + hits[1].cut) << "the status counts since it was cleared";
}

// Two meshes, four instances, two of them rotating and one translating fast; traced at four
// shutter times. The host reference: every instance's triangles carried into the world at the
// ray's time, brute force.
class TwoLevelScene : public TraceRays {
 protected:
  void SetUp() override {
    TraceRays::SetUp();
    const TriangleMesh sphere = bvh::test::cubeSphere(6), soup = bvh::test::randomSoup(400, 0.15f, 21);
    for (const TriangleMesh* mesh : {&sphere, &soup}) {
      scene::Mesh m;
      m.positions = mesh->positions;
      m.indices = mesh->indices;
      scene_.meshes.push_back(m);
    }
    scene_.materials.push_back({});
    const glm::vec3 places[4] = {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {-3, -1, 1}};
    for (uint32_t i = 0; i < 4; ++i) {
      scene::Node node;
      node.local.translation = places[i];
      scene_.nodes.push_back(node);
      scene_.instances.push_back({i % 2, i, 10 + i});
    }
    // Instance 1 spins a half turn about z over the shutter, instance 2 a quarter turn about x,
    // instance 3 moves 4 units in x.
    const auto rotation = [](float angle, glm::vec3 axis) {
      const glm::quat q = glm::angleAxis(angle, axis);
      return glm::vec4(q.x, q.y, q.z, q.w);
    };
    scene_.channels.push_back({1, scene::AnimationPath::Rotation, scene::Interpolation::Linear, {0.0f, 1.0f},
                               {rotation(0.0f, {0, 0, 1}), rotation(3.14159f, {0, 0, 1})}});
    scene_.channels.push_back({2, scene::AnimationPath::Rotation, scene::Interpolation::Linear, {0.0f, 1.0f},
                               {rotation(0.0f, {1, 0, 0}), rotation(1.5708f, {1, 0, 0})}});
    scene_.channels.push_back({3, scene::AnimationPath::Translation, scene::Interpolation::Linear, {0.0f, 1.0f},
                               {glm::vec4(-3, -1, 1, 0), glm::vec4(1, -1, 1, 0)}});
  }

  // Rays at each of the shutter times set, a third of them ignoring an object, against brute force.
  void expectRaysMatchBruteForce(const TraceScene& traceScene, std::span<const float> times);

  scene::Scene scene_;
  const std::vector<float> times_ = {0.0f, 0.3f, 0.65f, 1.0f};
};

TEST_F(TwoLevelScene, MotionBoundsHoldEveryInstanceAtEveryShutterTime) {
  vk::FrameRecorder frame(context());
  TraceScene traceScene(context(), scene_, frame);
  traceScene.setShutterTimes(scene_, times_, frame);
  const std::vector<gpu::BvhBox> boxes = traceScene.instanceBoxes().download<gpu::BvhBox>();
  const std::vector<gpu::BvhNode> topNodes = traceScene.downloadInstanceNodes();
  const Aabb root = bvh::boundsOf(topNodes.at(0));
  std::mt19937 rng(23);
  for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
    const Aabb box{glm::vec3(boxes[i].min), glm::vec3(boxes[i].max)};
    for (int sample = 0; sample < 8; ++sample) {
      const float t = times_[rng() % times_.size()];
      const glm::mat4 world = scene_.worldMatrixAt(scene_.instances[i].node, t);
      for (const glm::vec3& p : scene_.meshes[scene_.instances[i].mesh].positions) {
        const glm::vec3 w(world * glm::vec4(p, 1.0f));
        ASSERT_TRUE(box.contains(w)) << "instance " << i << " at t " << t;
        ASSERT_TRUE(root.contains(w)) << "top-level root, instance " << i << " at t " << t;
      }
    }
  }
  const bvh::Bvh top = traceScene.downloadInstanceTree();
  std::vector<Aabb> instanceBoxes;
  for (const gpu::BvhBox& b : boxes) instanceBoxes.push_back({glm::vec3(b.min), glm::vec3(b.max)});
  instanceBoxes.resize(scene_.instances.size());
  EXPECT_EQ(bvh::test::structuralProblem(top, instanceBoxes, HMB_BVH_MAX_INSTANCE_LEAF), "");
}

TEST_F(TwoLevelScene, RaysAtEachShutterTimeMatchBruteForceWithAndWithoutIgnoredObject) {
  vk::FrameRecorder frame(context());
  TraceScene traceScene(context(), scene_, frame);
  traceScene.setShutterTimes(scene_, times_, frame);
  EXPECT_FALSE(traceScene.topLevelHasInsertions()) << "a trace scene splits its top level when asked";
  expectRaysMatchBruteForce(traceScene, times_);
}

// Split from one still instance on (TraceScene::splitTopLevel): the moving instances inserted
// into the still one's tree trace as one tree over all. Built for other shutter times, the
// still one's tree serves these: only the insertions are made again
// (BvhBuildPass::recordInsertionsAgain), and every ray still finds what brute force finds. Moving
// the still instance builds it again; a threshold above the still instances builds one tree.
TEST_F(TwoLevelScene, ASplitTopLevelKeepsTheStillInstancesTreeAndTracesTheSame) {
  vk::FrameRecorder frame(context());
  TraceScene traceScene(context(), scene_, frame);
  traceScene.splitTopLevel(1);
  EXPECT_EQ(TraceScene::whyNotSplit(scene_, 1), "");
  traceScene.setShutterTimes(scene_, std::vector<float>{0.8f, 0.9f}, frame);
  EXPECT_TRUE(traceScene.topLevelHasInsertions()) << "a still instance and three moving ones";
  EXPECT_FALSE(traceScene.keepsStillInstanceTree());
  expectRaysMatchBruteForce(traceScene, std::vector<float>{0.8f, 0.9f});
  EXPECT_TRUE(traceScene.hasStillInstanceTreeOf(scene_));
  traceScene.setShutterTimes(scene_, times_, frame);
  EXPECT_TRUE(traceScene.keepsStillInstanceTree());
  expectRaysMatchBruteForce(traceScene, times_);
  scene_.nodes[0].local.translation.z += 0.5f;
  EXPECT_FALSE(traceScene.hasStillInstanceTreeOf(scene_));
  traceScene.setShutterTimes(scene_, times_, frame);
  EXPECT_FALSE(traceScene.keepsStillInstanceTree());
  EXPECT_TRUE(traceScene.topLevelHasInsertions());
  expectRaysMatchBruteForce(traceScene, times_);
  traceScene.splitTopLevel(2);
  EXPECT_NE(TraceScene::whyNotSplit(scene_, 2), "");
  traceScene.setShutterTimes(scene_, times_, frame);
  EXPECT_FALSE(traceScene.topLevelHasInsertions());
  expectRaysMatchBruteForce(traceScene, times_);
}

void TwoLevelScene::expectRaysMatchBruteForce(const TraceScene& traceScene, std::span<const float> times) {
  std::vector<TriangleMesh> world;  // per time: every instance's triangles, object id = instance
  std::vector<std::vector<uint32_t>> instanceBase(times.size());
  for (size_t k = 0; k < times.size(); ++k) {
    TriangleMesh mesh;
    for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
      instanceBase[k].push_back(mesh.triangleCount());
      mesh.append(scene_.meshes[scene_.instances[i].mesh], scene_.worldMatrixAt(scene_.instances[i].node, times[k]),
                  i);
    }
    world.push_back(std::move(mesh));
  }
  std::mt19937 rng(29);
  std::vector<gpu::TraceRay> rays;
  std::vector<Ray> hostRays;
  std::vector<uint32_t> rayTime, rayIgnore;
  const std::vector<Ray> mixed = bvh::test::mixedRays(world[0], 3000, 31);
  for (size_t r = 0; r < mixed.size(); ++r) {
    const auto k = static_cast<uint32_t>(r % times.size());
    const uint32_t ignore = r % 3 == 0 ? static_cast<uint32_t>(rng() % scene_.instances.size()) : HMB_IGNORE_NONE;
    rays.push_back(traceRay(mixed[r], k, ignore == HMB_IGNORE_NONE ? HMB_IGNORE_NONE : 10 + ignore));
    hostRays.push_back(mixed[r]);
    rayTime.push_back(k);
    rayIgnore.push_back(ignore);
  }
  const std::vector<gpu::BvhHit> hits = traceOnDevice(context(), traceScene, rays);
  Comparison c;
  uint32_t ignoredChecks = 0;
  for (size_t r = 0; r < rays.size(); ++r) {
    const uint32_t k = rayTime[r];
    bvh::TraceOptions options;
    options.ignoreObjectId = rayIgnore[r];
    const gpu::BvhHit expected = bvh::bruteForceClosestHit(world[k].view(), hostRays[r], options);
    // The host's triangle index into the flattened world -> (instance, mesh triangle).
    gpu::BvhHit expectedLocal = expected;
    uint32_t expectedInstance = HMB_NO_HIT;
    if (expected.triangle != HMB_NO_HIT) {
      expectedInstance = expected.objectId;
      const uint32_t mesh = scene_.instances[expectedInstance].mesh;
      expectedLocal.triangle =
          expected.triangle - instanceBase[k][expectedInstance] + traceScene.meshFirstTriangle()[mesh];
    }
    if (rayIgnore[r] != HMB_IGNORE_NONE && hits[r].triangle != HMB_NO_HIT) {
      ++ignoredChecks;
      EXPECT_NE(hits[r].instance, rayIgnore[r]) << "ray " << r << " hit the ignored object";
      EXPECT_EQ(hits[r].objectId, 10 + hits[r].instance);
    }
    // World-space triangles against object-space ones: t agrees to the rounding of the transform.
    c.add(r, expectedLocal, hits[r], expectedInstance, 2e-4f);
  }
  EXPECT_EQ(c.mismatches, 0u) << c.firstMismatch;
  EXPECT_GE(c.hits, 700u);
  EXPECT_GE(ignoredChecks, 200u);
}

}  // namespace
}  // namespace hmb::trace::test
