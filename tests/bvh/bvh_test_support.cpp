#include "tests/bvh/bvh_test_support.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <tuple>

#include "bvh/reference_builder.h"

namespace hmb::bvh::test {

void TriangleMesh::addTriangle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, uint32_t objectId) {
  const auto first = static_cast<uint32_t>(positions.size());
  positions.insert(positions.end(), {a, b, c});
  indices.insert(indices.end(), {first, first + 1, first + 2});
  objectIds.push_back(objectId);
}

void TriangleMesh::append(const scene::Mesh& mesh, const glm::mat4& transform, uint32_t objectId) {
  const auto first = static_cast<uint32_t>(positions.size());
  for (const glm::vec3& p : mesh.positions) positions.push_back(glm::vec3(transform * glm::vec4(p, 1.0f)));
  for (uint32_t index : mesh.indices) indices.push_back(first + index);
  objectIds.insert(objectIds.end(), mesh.triangleCount(), objectId);
}

Aabb TriangleMesh::bounds() const {
  Aabb box;
  for (const glm::vec3& p : positions) box.grow(p);
  return box;
}

std::vector<Aabb> randomBoxes(uint32_t count, uint32_t seed, bool someEmpty) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> place(-50.0f, 50.0f), size(0.01f, 3.0f);
  std::vector<Aabb> boxes;
  for (uint32_t i = 0; i < count; ++i) {
    const glm::vec3 c = i % 10 == 3 ? glm::vec3(1.0f, 2.0f, 3.0f) : glm::vec3(place(rng), place(rng), place(rng) * 0.1f);
    const glm::vec3 h(size(rng), size(rng), size(rng));
    boxes.push_back(someEmpty && i % 97 == 50 ? Aabb{} : Aabb{c - h, c + h});
  }
  return boxes;
}

TriangleMesh randomSoup(uint32_t count, float size, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), edge(-size, size);
  TriangleMesh mesh;
  for (uint32_t t = 0; t < count; ++t) {
    const glm::vec3 a(unit(rng), unit(rng), unit(rng));
    mesh.addTriangle(a, a + glm::vec3(edge(rng), edge(rng), edge(rng)), a + glm::vec3(edge(rng), edge(rng), edge(rng)),
                     1 + t % 7);
  }
  return mesh;
}

TriangleMesh grid(uint32_t cells, uint32_t seed) {
  std::mt19937 rng(seed);
  TriangleMesh mesh;
  for (uint32_t y = 0; y <= cells; ++y)
    for (uint32_t x = 0; x <= cells; ++x) mesh.positions.emplace_back(float(x), float(y), 0.0f);
  for (uint32_t y = 0; y < cells; ++y)
    for (uint32_t x = 0; x < cells; ++x) {
      const uint32_t v00 = y * (cells + 1) + x, v10 = v00 + 1, v01 = v00 + cells + 1, v11 = v01 + 1;
      if (rng() & 1)
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
      else
        mesh.indices.insert(mesh.indices.end(), {v00, v10, v01, v10, v11, v01});
      mesh.objectIds.insert(mesh.objectIds.end(), 2, 1 + (x + y) % 3);
    }
  return mesh;
}

TriangleMesh cubeSphere(uint32_t cells) {
  TriangleMesh mesh;
  // Vertices keyed by integer cube coordinates in [-cells, cells] (step 2), so an edge shared
  // by two faces uses the same vertices from both.
  std::map<std::tuple<int, int, int>, uint32_t> vertexOf;
  const auto vertex = [&](int x, int y, int z) {
    const auto [it, added] = vertexOf.try_emplace({x, y, z}, static_cast<uint32_t>(mesh.positions.size()));
    if (added) mesh.positions.push_back(glm::normalize(glm::vec3(float(x), float(y), float(z))));
    return it->second;
  };
  const int n = static_cast<int>(cells);
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {-n, n})
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          const auto at = [&](int a, int b) {
            int p[3];
            p[axis] = side;
            p[(axis + 1) % 3] = -n + 2 * a;
            p[(axis + 2) % 3] = -n + 2 * b;
            return vertex(p[0], p[1], p[2]);
          };
          const uint32_t v00 = at(i, j), v10 = at(i + 1, j), v01 = at(i, j + 1), v11 = at(i + 1, j + 1);
          mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
          mesh.objectIds.insert(mesh.objectIds.end(), 2, 1 + axis);
        }
  return mesh;
}

TriangleMesh sceneTriangles(const scene::Scene& scene, float t) {
  TriangleMesh mesh;
  for (const scene::Instance& instance : scene.instances)
    mesh.append(scene.meshes[instance.mesh], scene.worldMatrixAt(instance.node, t), instance.objectId);
  return mesh;
}

Bvh buildSah(const TriangleMesh& mesh, uint32_t maxLeafSize) {
  const PrimitiveBounds input = triangleBounds(mesh.view());
  return buildReferenceSah(input.bounds, input.centroids, BuildOptions{maxLeafSize});
}

Bvh buildMedianSplit(std::span<const Aabb> bounds, std::span<const glm::vec3> centroids, uint32_t maxLeafSize) {
  Bvh bvh;
  const auto count = static_cast<uint32_t>(bounds.size());
  if (count == 0) return bvh;
  bvh.primitiveIndices.resize(count);
  std::iota(bvh.primitiveIndices.begin(), bvh.primitiveIndices.end(), 0u);
  bvh.nodes.push_back({});
  struct Pending { uint32_t node, begin, end; };
  std::vector<Pending> pending{{0, 0, count}};
  while (!pending.empty()) {
    const Pending item = pending.back();
    pending.pop_back();
    auto first = bvh.primitiveIndices.begin() + item.begin, last = bvh.primitiveIndices.begin() + item.end;
    Aabb box, centres;
    for (auto it = first; it != last; ++it) box.grow(bounds[*it]), centres.grow(centroids[*it]);
    setBounds(bvh.nodes[item.node], box);
    if (item.end - item.begin <= maxLeafSize) {
      bvh.nodes[item.node].leftOrFirst = item.begin;
      bvh.nodes[item.node].count = item.end - item.begin;
      continue;
    }
    const glm::vec3 e = centres.extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    const uint32_t middle = item.begin + (item.end - item.begin) / 2;
    std::nth_element(first, bvh.primitiveIndices.begin() + middle, last,
                     [&](uint32_t a, uint32_t b) { return centroids[a][axis] < centroids[b][axis]; });
    const auto left = static_cast<uint32_t>(bvh.nodes.size());
    bvh.nodes[item.node].leftOrFirst = left;
    bvh.nodes[item.node].count = 0;
    bvh.nodes.resize(bvh.nodes.size() + 2);
    pending.push_back({left, item.begin, middle});
    pending.push_back({left + 1, middle, item.end});
  }
  return bvh;
}

namespace {

bool encloses(const Aabb& outer, const Aabb& inner) {
  return inner.empty() || (outer.contains(inner.min) && outer.contains(inner.max));
}

std::string describe(const Aabb& box) {
  std::ostringstream s;
  s << "[(" << box.min.x << ", " << box.min.y << ", " << box.min.z << ") - (" << box.max.x << ", " << box.max.y
    << ", " << box.max.z << ")]";
  return s.str();
}

}  // namespace

std::string structuralProblem(const Bvh& bvh, std::span<const Aabb> bounds, uint32_t maxLeafSize) {
  const size_t count = bounds.size();
  if (count == 0) return bvh.nodes.empty() && bvh.primitiveIndices.empty() ? "" : "empty input, non-empty BVH";
  if (bvh.nodes.empty()) return "no nodes";
  if (bvh.primitiveIndices.size() != count) return "primitive-index array has the wrong size";
  std::vector<uint32_t> nodeSeen(bvh.nodes.size(), 0), primitiveSeen(count, 0);
  std::vector<uint32_t> stack{HMB_BVH_ROOT};
  while (!stack.empty()) {
    const uint32_t index = stack.back();
    stack.pop_back();
    if (index >= bvh.nodes.size()) return "child index " + std::to_string(index) + " out of range";
    if (nodeSeen[index]++) return "node " + std::to_string(index) + " reached twice";
    const Node& node = bvh.nodes[index];
    const Aabb box = boundsOf(node);
    if (box.empty()) return "node " + std::to_string(index) + " has empty or NaN bounds";
    if (isLeaf(node)) {
      if (node.count > maxLeafSize) return "leaf " + std::to_string(index) + " holds " + std::to_string(node.count);
      if (size_t{node.leftOrFirst} + node.count > count) return "leaf " + std::to_string(index) + " out of range";
      for (uint32_t i = node.leftOrFirst; i < node.leftOrFirst + node.count; ++i) {
        const uint32_t primitive = bvh.primitiveIndices[i];
        if (primitive >= count) return "primitive index out of range";
        if (primitiveSeen[primitive]++) return "primitive " + std::to_string(primitive) + " in two leaves";
        if (!encloses(box, bounds[primitive]))
          return "leaf " + std::to_string(index) + " " + describe(box) + " misses primitive " +
                 std::to_string(primitive) + " " + describe(bounds[primitive]);
      }
      continue;
    }
    for (uint32_t child : {node.leftOrFirst, node.leftOrFirst + 1}) {
      if (child >= bvh.nodes.size()) return "child index " + std::to_string(child) + " out of range";
      if (!encloses(box, boundsOf(bvh.nodes[child])))
        return "node " + std::to_string(index) + " does not enclose child " + std::to_string(child);
      stack.push_back(child);
    }
  }
  for (size_t i = 0; i < bvh.nodes.size(); ++i)
    if (!nodeSeen[i]) return "node " + std::to_string(i) + " unreachable";
  for (size_t i = 0; i < count; ++i)
    if (!primitiveSeen[i]) return "primitive " + std::to_string(i) + " in no leaf";
  return "";
}

glm::vec3 randomUnitVector(std::mt19937& rng) {
  std::normal_distribution<float> normal;
  for (;;) {
    const glm::vec3 v(normal(rng), normal(rng), normal(rng));
    const float length = glm::length(v);
    if (length > 1e-3f) return v / length;
  }
}

glm::vec3 randomPointIn(const Aabb& box, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  return box.min + glm::vec3(unit(rng), unit(rng), unit(rng)) * (box.max - box.min);
}

glm::vec3 randomPointOnTriangle(const TriangleList& triangles, uint32_t triangle, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  float u = unit(rng), v = unit(rng);
  if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
  const auto [a, b, c] = triangles.vertices(triangle);
  return a + u * (b - a) + v * (c - a);
}

std::vector<Ray> mixedRays(const TriangleMesh& mesh, uint32_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  const TriangleList triangles = mesh.view();
  Aabb around = mesh.bounds();
  const glm::vec3 margin = 0.25f * around.extent() + 1e-3f;
  around.min -= margin, around.max += margin;
  std::uniform_int_distribution<uint32_t> pickTriangle(0, std::max(mesh.triangleCount(), 1u) - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const float diagonal = glm::length(around.extent());
  std::vector<Ray> rays;
  rays.reserve(count);
  for (uint32_t i = 0; i < count; ++i) {
    Ray ray;
    if (i % 2 == 0 || mesh.triangleCount() == 0) {
      ray.origin = randomPointIn(around, rng);
      ray.direction = randomUnitVector(rng) * (0.5f + unit(rng));  // not unit: t scales with it
    } else {
      const glm::vec3 target = randomPointOnTriangle(triangles, pickTriangle(rng), rng);
      ray.origin = target + randomUnitVector(rng) * diagonal;
      ray.direction = target - ray.origin;
    }
    if (i % 5 == 0) {  // a finite interval, sometimes starting past the first surface
      ray.tMin = 0.3f * unit(rng);
      ray.tMax = ray.tMin + 2.0f * unit(rng);
    }
    rays.push_back(ray);
  }
  return rays;
}

Agreement compareWithBruteForce(const Bvh& bvh, const TriangleList& triangles, std::span<const Ray> rays,
                                const TraceOptions& options) {
  Agreement result;
  const auto near = [](float a, float b) { return std::abs(a - b) <= 1e-5f * std::max({std::abs(a), std::abs(b), 1.0f}); };
  for (size_t i = 0; i < rays.size(); ++i) {
    const Hit expected = bruteForceClosestHit(triangles, rays[i], options);
    const Hit actual = closestHit(bvh, triangles, rays[i], options);
    ++result.rays;
    if (expected.triangle != HMB_NO_HIT) ++result.hits;
    const bool agree = expected.triangle == actual.triangle && expected.objectId == actual.objectId &&
                       (expected.triangle == HMB_NO_HIT ||
                        (near(expected.t, actual.t) && near(expected.u, actual.u) && near(expected.v, actual.v)));
    if (agree) continue;
    if (result.mismatches++ == 0) {
      std::ostringstream s;
      s << "ray " << i << ": brute force triangle " << expected.triangle << " t " << expected.t << ", BVH triangle "
        << actual.triangle << " t " << actual.t;
      result.firstMismatch = s.str();
    }
  }
  return result;
}

}  // namespace hmb::bvh::test
