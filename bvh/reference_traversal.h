// Closest-hit queries on the CPU: through a BVH, and by brute force over every triangle. Both
// use the same triangle test and the same order of hits, so they must agree exactly; the
// traversal kernels are checked against them.
#pragma once

#include <cstdint>

#include "bvh/bvh.h"
#include "bvh/bvh_layout.h"
#include "bvh/ray_intersection.h"
#include "bvh/triangle_list.h"

namespace hmb::bvh {

using Hit = gpu::BvhHit;

struct TraceOptions {
  // Hits on triangles of this object are skipped and the search goes on behind them (a reveal
  // ray looks for the first surface behind the object it starts on).
  uint32_t ignoreObjectId = HMB_IGNORE_NONE;
};

// The hit with the smallest t in [ray.tMin, ray.tMax]; among hits at the same t, the lowest
// triangle id (so ties, as through a shared edge or on duplicated triangles, do not depend on
// visiting order). A miss has triangle == objectId == HMB_NO_HIT and t == ray.tMax.
// `bvh` must be built over `triangles` (primitive i is triangle i).
Hit closestHit(const Bvh& bvh, const TriangleList& triangles, const Ray& ray, const TraceOptions& options = {});

Hit bruteForceClosestHit(const TriangleList& triangles, const Ray& ray, const TraceOptions& options = {});

// The judge of float traversals on real assets: a double-precision brute force over every
// triangle (both sides) of the nearest hit in [tMin, tMax], and of the nearest triangle whose
// edge the ray passes within `grazeMargin` of (a barycentric weight, so scale-free; inside or
// out), where float tests may rightly pick another triangle or miss.
struct ExactHit {
  double t = INFINITY;       // infinite: no hit
  double grazeT = INFINITY;  // infinite: no edge grazed
};
inline constexpr double kGrazeMargin = 1e-5;
ExactHit exactClosestHit(const TriangleList& triangles, const Ray& ray, double grazeMargin = kGrazeMargin);

}  // namespace hmb::bvh
