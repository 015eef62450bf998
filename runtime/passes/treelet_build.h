// Host side of the treelet builder (kernels/bvh/treelet_build_layout.h), the mesh builder under
// the GPU profile (vk::DeviceProfile::treeletMeshBuilds): Morton codes, a radix sort in four
// passes, a Karras radix tree, then treelets rebuilt and leaves chosen by the SAH on the way up,
// in kTreeletDispatches dispatches whatever the size, with nothing waited for or read back.
// BvhBuildPass records it into its own buffers (nodes, frames, primitive order, counters), so
// the trees are refitted, compacted and downloaded as the binned builder's are.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "hmblur/aabb.h"
#include "hmblur/buffer.h"
#include "kernels/bvh/treelet_build_layout.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb::passes {

// Bounds, codes, four sort passes, hierarchy, treelets, packing.
constexpr uint32_t kTreeletDispatches = 5 + HMB_TREELET_SORT_PASSES;
// The build's stages, as its dispatches are named when timed by kernel (the sort's four passes
// under one name).
inline constexpr const char* kTreeletStages[] = {"bounds", "codes", "sort", "hierarchy", "optimize", "pack"};

// Where a treelet build writes its trees: what BvhBuildPass keeps.
struct TreeletBuildTargets {
  const vk::Buffer* exactNodes = nullptr;   // BvhNode per output node
  const vk::Buffer* packedNodes = nullptr;  // BvhPackedNode per output node
  const vk::Buffer* frames = nullptr;       // BvhFrame per tree
  const vk::Buffer* primitives = nullptr;   // the primitive order the leaves index
  const vk::Buffer* counters = nullptr;     // gpu::BvhBuildCounters at its head
};

class TreeletBuild {
 public:
  TreeletBuild(const vk::Context& context, std::string name);

  // Records the build of the trees `roots` (first primitive, count; ranges apart) over `boxes`
  // into `frame`, every pass under the name `pass`, or with byKernel each dispatch under
  // "<pass>/<stage>" (kTreeletStages: where a build's time goes); `before` records what writes
  // the boxes.
  void record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes, uint32_t primitiveCount,
              std::span<const glm::uvec2> roots, uint32_t maxLeaf, const TreeletBuildTargets& targets,
              const std::function<void(vk::FrameRecorder&)>& before = {}, bool byKernel = false);
  // Frees the scratch (codes, the binary tree); the next build allocates it again.
  void release();
  // Tests: after a build, the sorted codes and their primitives (the first n entries of each).
  const vk::Buffer& sortedCodes() const { return scratch_.keys; }
  const vk::Buffer& sortedPrimitives() const { return scratch_.values; }

 private:
  const vk::Context& context_;
  std::string name_;
  // What a build works in, kept for the next build until release().
  struct Scratch {
    uint32_t capacity = 0, tileCapacity = 0, treeCapacity = 0;
    vk::Buffer tiles, trees, keys, values, digitCounts, nodes;
  };
  Scratch scratch_;
  vk::ComputeKernel boundsKernel_, codesKernel_, sortKernel_, hierarchyKernel_, optimizeKernel_, packKernel_;
};

}  // namespace hmb::passes
