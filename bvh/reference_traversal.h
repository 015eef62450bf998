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

}  // namespace hmb::bvh
