// What the device BVH and trace tests share: scenes made of test meshes, rays in the kernels'
// layout, and a trace through a TraceScene on the device.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "bvh/bvh.h"
#include "bvh/bvh_layout.h"
#include "bvh/ray_intersection.h"
#include "hmblur/context.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/trace_rays_pass.h"
#include "tests/bvh/bvh_test_support.h"

namespace hmb::trace::test {

// One mesh, one instance at the identity, object id 1.
scene::Scene sceneOf(const bvh::test::TriangleMesh& mesh);

gpu::TraceRay traceRay(const bvh::Ray& ray, uint32_t time = 0, uint32_t ignoreObjectId = HMB_IGNORE_NONE);

// Closest hits of `rays` through the scene (its shutter times must be set); flags: HMB_TRACE_*.
std::vector<gpu::BvhHit> traceOnDevice(
    const vk::Context& context, const TraceScene& scene, std::span<const gpu::TraceRay> rays, uint32_t flags = 0,
    passes::TraceRaysPass::TopLevel topLevel = passes::TraceRaysPass::TopLevel::WhereNeeded);

// Closest hits of `rays` through `mesh` as a one-instance scene at one shutter time.
std::vector<gpu::BvhHit> traceMesh(const vk::Context& context, const bvh::test::TriangleMesh& mesh,
                                   std::span<const bvh::Ray> rays);

// Levels below the root of the tree's deepest node, as HMB_BVH_MAX_DEPTH counts them (0 for a
// root alone or an empty tree; bvh::depthOf counts the root as one).
inline uint32_t levelsBelowRoot(const bvh::Bvh& tree) { return tree.nodes.empty() ? 0 : bvh::depthOf(tree) - 1; }

}  // namespace hmb::trace::test
