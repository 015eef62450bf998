#include "tests/trace/trace_harness.h"

#include <set>

#include "runtime/passes/trace_rays_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::trace::test {

scene::Scene sceneOf(const bvh::test::TriangleMesh& mesh) { return scene::singleMeshScene(mesh.positions, mesh.indices); }

std::vector<gpu::BvhHit> traceMesh(const vk::Context& context, const bvh::test::TriangleMesh& mesh,
                                   std::span<const bvh::Ray> rays) {
  const scene::Scene scene = sceneOf(mesh);
  vk::FrameRecorder frame(context);
  TraceScene traceScene(context, scene, frame);
  const float time = 0.0f;
  traceScene.setShutterTimes(scene, std::span(&time, 1), frame);
  std::vector<gpu::TraceRay> traceRays;
  for (const bvh::Ray& ray : rays) traceRays.push_back(traceRay(ray));
  return traceOnDevice(context, traceScene, traceRays);
}

gpu::TraceRay traceRay(const bvh::Ray& ray, uint32_t time, uint32_t ignoreObjectId) {
  return gpu::TraceRay{glm::vec4(ray.origin, ray.tMin), glm::vec4(ray.direction, ray.tMax), time, ignoreObjectId,
                       0u, 0u};
}

std::vector<gpu::BvhHit> traceOnDevice(const vk::Context& context, const TraceScene& scene,
                                       std::span<const gpu::TraceRay> rays, uint32_t flags, uint32_t stackSize) {
  const std::vector<gpu::TraceRay> rayList(rays.begin(), rays.end());
  const vk::Buffer rayBuffer = vk::uploadedBuffer(context, rayList, "test rays");
  const vk::Buffer hits(context, std::max<size_t>(rays.size(), 1) * sizeof(gpu::BvhHit), vk::MemoryUse::Device,
                        "test hits");
  const passes::TraceRaysPass pass(context, stackSize);
  vk::FrameRecorder frame(context);
  frame.begin();
  pass.record(frame, scene, rayBuffer, hits, static_cast<uint32_t>(rays.size()), flags);
  frame.submitAndWait();
  std::vector<gpu::BvhHit> out = hits.download<gpu::BvhHit>();
  out.resize(rays.size());
  return out;
}

std::string linkProblem(std::span<const gpu::BvhNode> nodes, std::span<const uint32_t> links, uint32_t root) {
  // The tree's nodes, found through the child indices.
  std::set<uint32_t> tree;
  std::vector<uint32_t> pending{root};
  while (!pending.empty()) {
    const uint32_t n = pending.back();
    pending.pop_back();
    if (n >= nodes.size()) return "child index " + std::to_string(n) + " out of range";
    if (!tree.insert(n).second) return "node " + std::to_string(n) + " reached twice through children";
    if (nodes[n].count == 0 && nodes[n].leftOrFirst != HMB_BVH_LINK_END) {
      pending.push_back(nodes[n].leftOrFirst);
      pending.push_back(nodes[n].leftOrFirst + 1);
    }
  }
  for (uint32_t octant = 0; octant < HMB_BVH_OCTANTS; ++octant) {
    std::set<uint32_t> seen;
    uint32_t node = root;
    while (node != HMB_BVH_LINK_END) {
      if (!tree.count(node)) return "octant " + std::to_string(octant) + ": link to node " + std::to_string(node) +
                                    " outside the tree";
      if (!seen.insert(node).second) return "octant " + std::to_string(octant) + ": node " + std::to_string(node) +
                                            " visited twice";
      const uint32_t link = links[size_t(node) * HMB_BVH_OCTANTS + octant];
      const gpu::BvhNode& n = nodes[node];
      if (n.count == 0 && n.leftOrFirst != HMB_BVH_LINK_END)
        node = n.leftOrFirst + ((link & HMB_BVH_LINK_RIGHT_FIRST) ? 1u : 0u);
      else
        node = link & HMB_BVH_LINK_NEXT_MASK;
    }
    if (seen.size() != tree.size())
      return "octant " + std::to_string(octant) + ": visited " + std::to_string(seen.size()) + " of " +
             std::to_string(tree.size()) + " nodes";
  }
  return "";
}

}  // namespace hmb::trace::test
