#include "tests/trace/trace_harness.h"

#include <algorithm>

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
                                       std::span<const gpu::TraceRay> rays, uint32_t flags,
                                       passes::TraceRaysPass::TopLevel topLevel) {
  const std::vector<gpu::TraceRay> rayList(rays.begin(), rays.end());
  const vk::Buffer rayBuffer = vk::uploadedBuffer(context, rayList, "test rays");
  const vk::Buffer hits(context, std::max<size_t>(rays.size(), 1) * sizeof(gpu::BvhHit), vk::MemoryUse::Device,
                        "test hits");
  const passes::TraceRaysPass pass(context);
  vk::FrameRecorder frame(context);
  frame.begin();
  pass.record(frame, scene, rayBuffer, hits, static_cast<uint32_t>(rays.size()), flags, topLevel);
  frame.submitAndWait();
  std::vector<gpu::BvhHit> out = hits.download<gpu::BvhHit>();
  out.resize(rays.size());
  return out;
}

}  // namespace hmb::trace::test
