// Embree as the CPU anchor of the BVH benchmark: how long Intel's builders take over the same
// triangles, how good a tree its SAH builder makes by our own SAH cost, and how fast its
// traversal answers the same closest-hit queries.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_layout.h"
#include "bvh/ray_intersection.h"
#include "bvh/triangle_list.h"

namespace hmb::bench {

// False when built without Embree: then runEmbree throws.
bool embreeAvailable();
// Version of the Embree library actually loaded, e.g. "3.13.5"; "" when unavailable.
std::string embreeVersion();

// One build time and one trace time, for reports that pair them.
struct EmbreeSample {
  double buildSeconds;
  double traceSeconds;
};

struct EmbreeRun {
  // rtcCommitScene of one triangle geometry (default build quality), one per repeat. Creating
  // the scene and attaching the geometry is not counted.
  std::vector<double> sceneBuildSeconds;
  // rtcBuildBVH with our SAH costs and leaf size, one per repeat (see the .cpp for the quality).
  std::vector<double> bvhBuildSeconds;
  // The tree of the last rtcBuildBVH, in our layout, so that bvh::sahCost() can judge it
  // against our builders.
  bvh::Bvh bvh;
  // Tracing every ray of the batch through the committed scene, one per repeat.
  std::vector<double> traceSeconds;
  // Closest hit per ray of the last repeat: triangle = Embree's primID, objectId from the
  // triangle list; a miss has triangle == objectId == HMB_NO_HIT and t == ray.tMax.
  std::vector<gpu::BvhHit> hits;
};

// Builds and traces `warmup` untimed times, then `repeats` timed times. `threads` is both
// Embree's worker count and the number of threads the rays are split over. Throws hmb::Error
// when Embree is unavailable or reports an error.
EmbreeRun runEmbree(const bvh::TriangleList& triangles, std::span<const bvh::Ray> rays, int threads, int warmup,
                    int repeats);

}  // namespace hmb::bench
