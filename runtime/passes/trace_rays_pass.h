// Host side of kernels/trace/trace_rays: the closest hit of each ray through a TraceScene.
#pragma once

#include <cstdint>
#include <memory>

#include "kernels/trace/trace_layout.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb {
class TraceScene;
}
namespace hmb::vk {
class Buffer;
class FrameRecorder;
}

namespace hmb::passes {

class TraceRaysPass {
 public:
  static constexpr const char* kName = "trace-rays";

  explicit TraceRaysPass(const vk::Context& context);

  enum class TopLevel { WhereNeeded, Always };

  // rays: TraceRay[rayCount]; hits: BvhHit[rayCount]. The scene needs its shutter times set.
  // flags: HMB_TRACE_* (kernels/trace/trace_layout.h), e.g. culling back faces as the rasterizer does.
  // A scene of one instance is traced without the top-level walk unless `topLevel` is Always.
  void record(vk::FrameRecorder& frame, const TraceScene& scene, const vk::Buffer& rays, const vk::Buffer& hits,
              uint32_t rayCount, uint32_t flags = 0, TopLevel topLevel = TopLevel::WhereNeeded) const;

 private:
  const vk::Context& context_;
  mutable std::unique_ptr<vk::ComputeKernel> kernels_[2];  // [walks the top level], each made on first use
};

}  // namespace hmb::passes
