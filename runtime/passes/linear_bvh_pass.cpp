#include "runtime/passes/linear_bvh_pass.h"

#include <algorithm>
#include <array>

#include "bvh/packed_node.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

LinearBvhPass::LinearBvhPass(const vk::Context& context, std::string name)
    : context_(context),
      name_(std::move(name)),
      sortKernel_(context, kernels::kernel("bvh/linear_sort_keys")),
      hierarchyKernel_(context, kernels::kernel("bvh/linear_hierarchy")),
      boundsKernel_(context, kernels::kernel("bvh/linear_bounds"),
                    std::array<uint32_t, 1>{context.profile().uniformAtomicRounds ? 1u : 0u}),
      packKernel_(context, kernels::kernel("bvh/linear_pack")) {}

void LinearBvhPass::reserve(uint32_t primitiveCount) {
  if (primitiveCount <= capacity_ && packedNodes_.handle()) return;
  const uint64_t n = std::max(primitiveCount, 1u), nodes = 2 * n;
  codes_ = vk::Buffer(context_, 2 * n * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " codes");
  primitives_ = vk::Buffer(context_, 2 * n * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " primitives");
  links_ = vk::Buffer(context_, nodes * sizeof(gpu::LinearBvhLink), vk::MemoryUse::Device, name_ + " links");
  exact_ = vk::Buffer(context_, nodes * sizeof(gpu::BvhBox), vk::MemoryUse::Device, name_ + " exact bounds");
  packedNodes_ = vk::Buffer(context_, nodes * sizeof(gpu::BvhPackedNode), vk::MemoryUse::Device, name_ + " nodes");
  frames_ = vk::Buffer(context_, sizeof(gpu::BvhFrame), vk::MemoryUse::Device, name_ + " frame");
  capacity_ = static_cast<uint32_t>(n);
}

void LinearBvhPass::record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                           uint32_t primitiveCount, const std::function<void(vk::FrameRecorder&)>& before) {
  if (primitiveCount > HMB_LINEAR_BVH_MAX_PRIMITIVES)
    throw Error(name_ + ": " + std::to_string(primitiveCount) + " primitives, more than the linear builder's " +
                std::to_string(HMB_LINEAR_BVH_MAX_PRIMITIVES));
  if (boxes.size() < uint64_t(primitiveCount) * sizeof(gpu::BvhBox))
    throw Error(name_ + ": the boxes' buffer holds fewer than " + std::to_string(primitiveCount) + " boxes");
  reserve(primitiveCount);
  primitiveCount_ = primitiveCount;
  const gpu::LinearBvhParams params{primitiveCount, 0u, 0u, 0u};
  const uint32_t n = primitiveCount;
  frame.fill(pass, links_, 0u);
  if (before) before(frame);
  frame.dispatch(pass, sortKernel_,
                 {{HMB_LINEAR_SORT_BINDING_BOXES, &boxes},
                  {HMB_LINEAR_SORT_BINDING_CODES, &codes_},
                  {HMB_LINEAR_SORT_BINDING_PRIMITIVES, &primitives_}},
                 params, {1, 1, 1});
  frame.dispatch(pass, hierarchyKernel_,
                 {{HMB_LINEAR_HIERARCHY_BINDING_CODES, &codes_}, {HMB_LINEAR_HIERARCHY_BINDING_LINKS, &links_}}, params,
                 vk::foldedGroups(vk::groupsFor(std::max(n, 2u) - 1, HMB_LINEAR_BVH_GROUP)));
  frame.dispatch(pass, boundsKernel_,
                 {{HMB_LINEAR_BOUNDS_BINDING_BOXES, &boxes},
                  {HMB_LINEAR_BOUNDS_BINDING_PRIMITIVES, &primitives_},
                  {HMB_LINEAR_BOUNDS_BINDING_LINKS, &links_},
                  {HMB_LINEAR_BOUNDS_BINDING_EXACT, &exact_}},
                 params, vk::foldedGroups(vk::groupsFor(n, HMB_LINEAR_BVH_GROUP)));
  frame.dispatch(pass, packKernel_,
                 {{HMB_LINEAR_PACK_BINDING_LINKS, &links_},
                  {HMB_LINEAR_PACK_BINDING_EXACT, &exact_},
                  {HMB_LINEAR_PACK_BINDING_FRAMES, &frames_},
                  {HMB_LINEAR_PACK_BINDING_PACKED_NODES, &packedNodes_}},
                 params, vk::foldedGroups(vk::groupsFor(nodeCount(), HMB_LINEAR_BVH_GROUP)));
}

std::vector<gpu::BvhNode> LinearBvhPass::downloadNodes() const {
  const std::vector<gpu::BvhPackedNode> packed = packedNodes_.download<gpu::BvhPackedNode>();
  const gpu::BvhFrame frame = frames_.download<gpu::BvhFrame>().at(0);
  std::vector<gpu::BvhNode> nodes(nodeCount());
  for (uint32_t i = 0; i < nodes.size(); ++i) nodes[i] = bvh::unpackNode(packed.at(i), frame);
  return nodes;
}

bvh::Bvh LinearBvhPass::download() const {
  bvh::Bvh out;
  if (primitiveCount_ == 0) return out;
  out.nodes = downloadNodes();
  const std::vector<uint32_t> primitives = primitives_.download<uint32_t>();
  out.primitiveIndices.assign(primitives.begin(), primitives.begin() + primitiveCount_);
  return out;
}

}  // namespace hmb::passes
