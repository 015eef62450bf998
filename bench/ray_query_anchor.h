// The driver's own ray tracing as an anchor of the bvh suite: its acceleration-structure build
// (VK_KHR_acceleration_structure) and its ray queries (VK_KHR_ray_query) over the same
// triangles and rays as our kernels and Embree. On Mesa >= 24.1 lavapipe that is lavapipe's
// own BVH; on a GPU, its ray-tracing hardware. A benchmark anchor only: the renderer never
// uses a ray-tracing extension, and the anchor runs on a logical device of its own, so the
// renderer's device never enables one.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "bvh/bvh_layout.h"
#include "bvh/ray_intersection.h"
#include "bvh/triangle_list.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

class RayQueryAnchor {
 public:
  // Why the context's physical device cannot be the anchor (a missing extension or feature),
  // or "" when it can.
  static std::string unavailableReason(const vk::Context& context);

  // A logical device of its own on the context's physical device and queue family. Throws
  // hmb::Error when unavailableReason() is not empty.
  explicit RayQueryAnchor(const vk::Context& context);
  ~RayQueryAnchor();
  RayQueryAnchor(const RayQueryAnchor&) = delete;
  RayQueryAnchor& operator=(const RayQueryAnchor&) = delete;

  // Builds the triangles' bottom-level structure (prefer fast trace, opaque) and a top level
  // of one identity instance over it, replacing any earlier build. Returns the device time of
  // the two builds, in milliseconds, from timestamps around them.
  double build(const bvh::TriangleList& triangles);

  // Traces every ray through the last build; returns the device time of the dispatch in
  // milliseconds. The hits: triangle = the triangle's index in the list, objectId 0, or
  // HMB_NO_HIT for both and t == tMax on a miss.
  double trace(std::span<const bvh::Ray> rays, std::vector<gpu::BvhHit>& hits);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace hmb::bench
