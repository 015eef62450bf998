// The CPU reference builder: top-down full-sweep SAH, the quality yardstick for the device
// builder and the BVH the tests trust.
#pragma once

#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "hmblur/aabb.h"

namespace hmb::bvh {

struct BuildOptions {
  // Leaves hold at most this many primitives; a node that may be a leaf becomes one when no
  // split is cheaper by the SAH.
  uint32_t maxLeafSize = 4;
  float traversalCost = 1.0f;
  float intersectionCost = 1.0f;
  SahCosts costs() const { return {traversalCost, intersectionCost}; }
};

// Builds over primitives 0..n-1 given their bounds and centroids (the points they are sorted
// by; usually the bounds' centres). At each node every split position along the centroid
// order of each axis is costed; ties prefer the split nearest the middle, so coincident or
// degenerate primitives still give a balanced tree. Iterative: no recursion depth limit.
// Throws std::invalid_argument when the two spans differ in size.
Bvh buildReferenceSah(std::span<const Aabb> primitiveBounds, std::span<const glm::vec3> centroids,
                      const BuildOptions& options = {});

}  // namespace hmb::bvh
