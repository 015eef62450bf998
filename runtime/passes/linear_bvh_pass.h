// Host side of the linear BVH builder (kernels/bvh/linear_bvh_layout.h): one tree over up to
// HMB_LINEAR_BVH_MAX_PRIMITIVES primitive boxes, a primitive a leaf, recorded into a frame in
// four dispatches whatever the count, with nothing read back: the top level's builder under the
// GPU profile (vk::DeviceProfile::linearTopLevel), where the binned builder (BvhBuildPass)
// records two dispatches a level. Its trees are Morton-ordered, not split by SAH: cheaper to
// build, somewhat dearer to walk.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "bvh/bvh.h"
#include "hmblur/buffer.h"
#include "kernels/bvh/linear_bvh_layout.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

class LinearBvhPass {
 public:
  LinearBvhPass(const vk::Context& context, std::string name);

  // Records the build over `boxes` (BvhBox per primitive, primitiveCount of them) into `frame`
  // (begun, not submitted here), every pass under the name `pass`; `before` records what writes
  // the boxes. Throws hmb::Error past HMB_LINEAR_BVH_MAX_PRIMITIVES.
  void record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes, uint32_t primitiveCount,
              const std::function<void(vk::FrameRecorder&)>& before = {});

  // Valid once the recorded build ran: the packed nodes (the root at 0), the tree's frame and
  // the primitive order the leaves index (the first primitiveCount entries).
  const vk::Buffer& nodes() const { return packedNodes_; }
  const vk::Buffer& frames() const { return frames_; }
  const vk::Buffer& primitives() const { return primitives_; }
  uint32_t primitiveCount() const { return primitiveCount_; }
  uint32_t nodeCount() const { return primitiveCount_ == 0 ? 1u : 2u * primitiveCount_ - 1u; }

  // Tests: the sorted Morton codes (the first primitiveCount entries of the codes' buffer).
  const vk::Buffer& sortedCodes() const { return codes_; }
  // The built tree on the host, as bvh::sahCost and the CPU checks take it (the packed bounds,
  // as traversal sees them), and every node unpacked as indexed on the device.
  bvh::Bvh download() const;
  std::vector<gpu::BvhNode> downloadNodes() const;

 private:
  void reserve(uint32_t primitiveCount);

  const vk::Context& context_;
  std::string name_;
  uint32_t primitiveCount_ = 0;
  uint32_t capacity_ = 0;  // primitives the buffers hold
  vk::Buffer codes_, primitives_, links_, exact_, packedNodes_, frames_;
  vk::ComputeKernel sortKernel_, hierarchyKernel_, boundsKernel_, packKernel_;
};

}  // namespace hmb::passes
