// A view of indexed triangles with an object id each: what the reference traversal traces and
// what the builders take bounds from.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/aabb.h"

namespace hmb::bvh {

struct TriangleList {
  std::span<const glm::vec3> positions;
  std::span<const uint32_t> indices;    // 3 per triangle
  std::span<const uint32_t> objectIds;  // 1 per triangle; empty: every triangle is object 0

  uint32_t triangleCount() const { return static_cast<uint32_t>(indices.size() / 3); }
  std::array<glm::vec3, 3> vertices(uint32_t triangle) const {
    const size_t first = size_t{triangle} * 3;
    return {positions[indices[first]], positions[indices[first + 1]], positions[indices[first + 2]]};
  }
  uint32_t objectId(uint32_t triangle) const { return objectIds.empty() ? 0u : objectIds[triangle]; }
};

// Per-triangle bounds and their centres: the builders' input.
struct PrimitiveBounds {
  std::vector<Aabb> bounds;
  std::vector<glm::vec3> centroids;
};

PrimitiveBounds triangleBounds(const TriangleList& triangles);

}  // namespace hmb::bvh
