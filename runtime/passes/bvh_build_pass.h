// Host side of the device BVH builder (kernels/bvh/): begin_build, then build_level and
// size_build_dispatch once per tree level, then build_small_tasks for the small subtrees the
// levels set aside. Builds one or more trees over one array of
// primitive boxes; tree r covers primitives roots[r] = (first, count) and is rooted at node r.
//
// How deep the trees go is only known on the device, so build() records a batch of levels,
// submits, and reads the task count back; a tree deeper than the batch gets another batch.
// A level without tasks dispatches no groups. record() instead records the whole build into a
// frame, with no submission or read-back: it bounds the trees' depth by the levels it records.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "bvh/bvh.h"
#include "hmblur/buffer.h"
#include "kernels/bvh/bvh_build_layout.h"
#include "runtime/passes/treelet_build.h"
#include "runtime/vulkan/binding.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
struct FrameTimings;
}

namespace hmb::passes {

// Host bounds as the builder takes them (BvhBox per primitive), for builds and refits over boxes
// made on the host.
std::vector<gpu::BvhBox> bvhBoxes(std::span<const Aabb> bounds);

struct BvhBuildStats {
  uint32_t nodes = 0;
  uint32_t leaves = 0;
  uint32_t levels = 0;       // tree levels built (the deepest leaf's depth, counting the root as 1)
  uint32_t submissions = 0;  // batches of levels submitted
  double deviceMilliseconds = 0.0;  // sum of the batches' frame times (0 without timestamps)
  std::vector<double> levelMilliseconds;  // build_level's time at each level (empty without timestamps)
  uint32_t smallTasks = 0;                // subtrees build_small_tasks finished
  double smallTaskMilliseconds = 0.0;     // its time
  // The treelet shape's build() by stage (kTreeletStages, in order; empty without timestamps).
  std::vector<std::pair<std::string, double>> stageMilliseconds;
};

// How build_level's workgroups are shaped (kernels/bvh/bvh_build_layout.h): their size and
// whether large tasks bin into per-lane copies of the bins; and the largest task
// build_small_tasks takes whole.
struct BvhBuildShape {
  uint32_t levelGroup = HMB_BVH_LEVEL_GROUP;
  bool laneBins = true;
  uint32_t smallTask = HMB_BVH_SMALL_TASK;
  // Built by the treelet builder instead (passes::TreeletBuild): a constant number of dispatches
  // whatever the size, nothing read back, where the levels record two dispatches each and a
  // build waits on the host between batches of them. The mesh builds' choice under the GPU
  // profile (vk::DeviceProfile::treeletMeshBuilds); the fields above then go unused.
  bool treelets = false;
  // The shape the device profile chooses (vk::DeviceProfile): the CPU profile's 8 lanes and
  // per-lane bins, or the GPU profile's warp or wave (the subgroup size, 32 to 64, within the
  // device's workgroup limit) binning with shared atomics.
  static BvhBuildShape forDevice(const vk::Context& context);
  // The profile's shape for a top level over instances: under the CPU profile a tree of up to
  // HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU instances is built by one invocation, with no level.
  static BvhBuildShape forTopLevel(const vk::Context& context);
  // Small tasks larger than HMB_BVH_SMALL_TASK (the CPU top level's) leave their nodes' bounds
  // to be packed after them, a lane per node (HMB_SPEC_BVH_PACK_LATER).
  bool packsLater() const { return smallTask > HMB_BVH_SMALL_TASK; }
  // "8 lanes, per-lane bins" / "32 lanes, shared atomics" (and ", small tasks of up to N"
  // where N is not HMB_BVH_SMALL_TASK), or "treelets": for reports.
  std::string describe() const;
};

class BvhBuildPass {
 public:
  static constexpr const char* kBegin = "bvh-begin-build";
  static constexpr const char* kLevel = "bvh-build-level";
  static constexpr const char* kSizeDispatch = "bvh-size-build-dispatch";
  static constexpr const char* kSmallTasks = "bvh-build-small-tasks";
  static constexpr const char* kPackDeferred = "bvh-pack-deferred-nodes";
  static constexpr const char* kCompact = "bvh-compact";
  static constexpr const char* kRefitParents = "bvh-refit-parents";
  static constexpr const char* kRefitPlaces = "bvh-refit-places";
  static constexpr const char* kRefitBounds = "bvh-refit-bounds";
  static constexpr const char* kRefitPack = "bvh-refit-pack";
  static constexpr const char* kTreelets = "bvh-treelet-build";
  // Levels recorded in the first submission: what a tree of the largest root's size needs
  // when its splits are not too uneven (log2 of its primitives, plus a margin), at most
  // kMaxLevelsPerSubmission. A deeper tree takes more submissions of kLevelsPerLaterSubmission
  // levels each. Every level recorded past the deepest costs two dispatches that do nothing, so
  // a batch sized to the tree is cheaper than the largest batch (bench/results/bvh-top-level/).
  static constexpr uint32_t kLevelMargin = 6;
  static constexpr uint32_t kMaxLevelsPerSubmission = 40;
  static constexpr uint32_t kLevelsPerLaterSubmission = 16;
  static uint32_t firstSubmissionLevels(uint32_t largestTree);

  // Leaves hold at most maxLeaf primitives (HMB_BVH_MAX_LEAF for triangles,
  // HMB_BVH_MAX_INSTANCE_LEAF for instances). The shape defaults to the device's; tests build
  // with the other shape to check that both make the same trees.
  BvhBuildPass(const vk::Context& context, std::string name, uint32_t maxLeaf);
  BvhBuildPass(const vk::Context& context, std::string name, uint32_t maxLeaf, const BvhBuildShape& shape);
  const BvhBuildShape& shape() const { return shape_; }
  // Tests: bound the trees' depth tighter than HMB_BVH_MAX_DEPTH (what traversal's stack holds).
  // The treelet shape's trees are as deep as their codes make them (at most
  // HMB_TREELET_MAX_HEIGHT nodes): it takes no tighter bound.
  void limitDepth(uint32_t levels);
  // The deepest subtree one invocation of build_small_tasks may build over taskPrimitives
  // primitives: HMB_BVH_MAX_DEPTH, or less where it would loop past the driver's loop budget
  // (vk::DeviceProfile::loopBudget: lavapipe 22.3 ends an invocation's loops silently after
  // 65535 iterations and leaves the subtree unbuilt). Every build bounds its trees' depth by it
  // for its largest small task (within lavapipe 22.3's budget the CPU top level's tasks of up
  // to 512 instances, packed later, to 31 levels, bistro's 321 to 53; tasks that pack their
  // nodes keep 64 up to 245 primitives). Without a budget: HMB_BVH_MAX_DEPTH.
  static uint32_t smallTaskDepthBound(uint32_t taskPrimitives, bool packsLater, std::optional<uint32_t> loopBudget);
  // The depth bound of a build whose largest tree holds largestTree primitives: the pass's
  // (limitDepth), within smallTaskDepthBound of its largest small task.
  uint32_t depthBound(uint32_t largestTree) const;

  // Builds the trees over `boxes` (BvhBox per primitive, primitiveCount of them) with
  // the given roots, whose ranges must not overlap. `before` records passes that must run
  // first in the first submission (those that write the boxes). Returns the stats, which
  // also stay in stats().
  const BvhBuildStats& build(vk::FrameRecorder& frame, const vk::Buffer& boxes, uint32_t primitiveCount,
                             std::span<const glm::uvec2> roots,
                             const std::function<void(vk::FrameRecorder&)>& before = {});

  // The build recorded into `frame` (begun, not submitted here), every pass under the name
  // `pass`: nothing waits and nothing is read back, for a per-frame tree in an engine's
  // command buffer. It bounds the trees' depth by recordedDepthBound() (a SAH split that
  // would go deeper is halved, as at HMB_BVH_MAX_DEPTH) and records the levels that bound can
  // need (it, less the levels below the deepest task too large for build_small_tasks).
  // Levels without tasks dispatch no groups; on lavapipe each costs two empty dispatches.
  // stats() stays empty until readRecordedCounts(), and what needs the node count (refit(),
  // compact(), download()) waits for it too.
  void record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes, uint32_t primitiveCount,
              std::span<const glm::uvec2> roots, const std::function<void(vk::FrameRecorder&)>& before = {});
  // The depth bound record() gives trees of up to largestTree primitives: the levels build()'s
  // first submission records, at most the pass's depth bound.
  uint32_t recordedDepthBound(uint32_t largestTree) const;
  // A tree kept from frame to frame with a few primitives inserted into it in each, for a top
  // level over instances of which most stand still: recordKeptWithInsertions records a build over
  // the first `kept` primitives of `order` (boxes indexed by primitive; the leaves index
  // `order`), as record() does, saves its exact nodes, and inserts the rest of the order, at
  // most HMB_BVH_MAX_INSERTED (kernels/bvh/insert_primitives.comp); recordInsertionsAgain
  // restores the kept tree and inserts the rest again from new boxes (the kept primitives'
  // boxes as they were). One dispatch, where a build of hundreds of primitives is one
  // invocation's work on a CPU device. Such a tree is not refitted or compacted; stats() gives
  // its node count with the insertions, its leaf and level counts as the kept tree's build.
  void recordKeptWithInsertions(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                                std::span<const uint32_t> order, uint32_t kept,
                                const std::function<void(vk::FrameRecorder&)>& before = {});
  void recordInsertionsAgain(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                             const std::function<void(vk::FrameRecorder&)>& before = {});
  // The last build kept a tree and inserted into it.
  bool hasInsertions() const { return inserted_; }
  // After a recorded build completed on the device: its node, leaf and level counts read back
  // into stats() (tests, reports), with the device time its frame measured.
  const BvhBuildStats& readRecordedCounts(double deviceMilliseconds = 0.0);

  // Moves the trees of the last build into buffers of their own size and frees the build's
  // scratch (the primitive array's second half, the task lists, the exact nodes): for trees built once and
  // kept, which then hold about half the worst case allocated for a build. The next build
  // allocates afresh. Adds its copy time to stats().deviceMilliseconds.
  void compact(vk::FrameRecorder& frame);

  // Refits the last build's trees to new boxes of the same primitives (a deforming mesh): every
  // node's bounds from its leaves up, each tree's frame from its root's new box, the topology
  // and primitive order kept. Compacted trees refit too. Returns the device time (ms).
  // The SAH cost drifts as the primitives move from where the build split them; a build
  // restores it.
  // Only `trees` are refitted (all when empty): the others keep their bounds, whatever their
  // boxes say. The first refit after a build also finds each node's parent, depth and root
  // (a round trip through the host), kept for the next refits; their nodes are sorted by depth
  // again only when the trees asked for change. Each refit then bounds every node of its trees
  // once, a dispatch per depth, and packs them.
  double refit(vk::FrameRecorder& frame, const vk::Buffer& boxes, std::span<const uint32_t> trees = {});
  // The same in two steps, for a frame that must not wait (an engine's): prepareRefit does what
  // the host does (the first refit's round trip, submitted on `frame` and waited for; the
  // sorting) and returns the device milliseconds it waited for, 0 once prepared;
  // recordRefit records the refit's dispatches into a begun frame, with no submission, under
  // the name `pass` (empty: kRefitBounds and kRefitPack).
  double prepareRefit(vk::FrameRecorder& frame, std::span<const uint32_t> trees = {});
  void recordRefit(vk::FrameRecorder& frame, const vk::Buffer& boxes, std::string_view pass = {}) const;

  const BvhBuildStats& stats() const { return stats_; }
  // The trees' buffers on the device: exact and packed nodes, primitive indices and
  // frames, allocated for the worst case (a leaf per primitive, primitive indices twice for the
  // partitions) until compact() fits them to the trees and frees the exact nodes.
  uint64_t allocatedTreeBytes() const {
    return nodes_.size() + packedNodes_.size() + primitives_.size() + frames_.size();
  }
  // What the last build filled of them: its packed nodes, one index per primitive, a frame per
  // tree.
  uint64_t usedTreeBytes() const;
  // Valid after build(): the packed nodes (tree r rooted at node r), each tree's frame, and the
  // primitive order the leaves index (the first primitiveCount entries).
  const vk::Buffer& nodes() const { return packedNodes_; }
  const vk::Buffer& frames() const { return frames_; }
  const vk::Buffer& primitives() const { return primitives_; }
  uint32_t primitiveCount() const { return primitiveCount_; }

  // The built nodes and primitive order on the host, tree `root` re-rooted at node 0 with
  // primitive indices relative to its range (what bvh::sahCost and the CPU checks take). The
  // bounds are the packed ones, as traversal sees them.
  bvh::Bvh download(uint32_t root = 0) const;
  // Every node unpacked, as indexed on the device.
  std::vector<gpu::BvhNode> downloadNodes() const;
  // The exact float nodes the build kept before packing (tests); gone after compact().
  const vk::Buffer& exactNodes() const { return nodes_; }
  // The treelet shape's builder (tests: its sorted codes), null for the binned shape.
  const TreeletBuild* treeletBuild() const { return treelets_.get(); }

 private:
  // Every tree goes to build_small_tasks from begin_build (kernels/bvh/begin_build.comp).
  bool allSmall(uint32_t largestTree) const { return largestTree <= shape_.smallTask; }
  void reserve(uint32_t primitiveCount, uint32_t treeCount);
  // What build() and record() share: checks, buffers, the first counters and parameters.
  struct Start {
    gpu::BvhBuildCounters counters{};
    gpu::BvhBuildParams params{};
    vk::Bindings buffers;
    glm::uvec3 rootGroups{0u};
    uint32_t largestTree = 0;
  };
  Start start(const vk::Buffer& boxes, uint32_t primitiveCount, std::span<const glm::uvec2> roots,
              uint32_t depthBound);
  // The build kernels' buffers (kernels/bvh/bvh_build_layout.h), over `boxes`.
  vk::Bindings buildBindings(const vk::Buffer& boxes) const;
  // record()'s passes from begin_build to build_small_tasks.
  void recordTrees(vk::FrameRecorder& frame, std::string_view pass, Start& s,
                   const std::function<void(vk::FrameRecorder&)>& before);
  // The treelet builder's passes into the build's buffers.
  void recordTreelets(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                      const std::function<void(vk::FrameRecorder&)>& before, bool byKernel = false);
  // insert_primitives over the kept tree.
  void recordInsertions(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes);
  void takeCounts(const gpu::BvhBuildCounters& counters);
  // pack_deferred_nodes after build_small_tasks, where the shape packs later.
  void recordDeferredPacking(vk::FrameRecorder& frame, std::string_view pass, const Start& s);
  void prepareRefits(vk::FrameRecorder& frame);
  void sortRefitNodes(std::span<const uint32_t> trees);

  // What refits of the last build's trees keep (empty until the first refit).
  struct Refits {
    vk::Buffer roots;   // roots_ on the device
    vk::Buffer exact;   // BvhBox per node: the refitted exact bounds
    vk::Buffer places;  // uvec2 per node: depth, root
    std::vector<glm::uvec2> hostPlaces;  // the same on the host
    std::vector<uint32_t> trees;         // the trees refitted (empty: all)
    vk::Buffer order;   // their nodes by depth
    std::vector<uint32_t> depthStart;  // depth d's nodes: order[depthStart[d] .. depthStart[d + 1])
    double preparedMilliseconds = 0.0;
  };

  const vk::Context& context_;
  std::string name_;
  uint32_t maxLeaf_;
  uint32_t maxDepth_ = HMB_BVH_MAX_DEPTH;
  BvhBuildShape shape_;
  vk::ComputeKernel beginKernel_;
  vk::ComputeKernel levelKernel_;
  vk::ComputeKernel sizeDispatchKernel_;
  vk::ComputeKernel smallTasksKernel_;
  vk::ComputeKernel packDeferredKernel_;
  vk::ComputeKernel refitParentsKernel_;
  vk::ComputeKernel refitPlacesKernel_;
  vk::ComputeKernel refitBoundsKernel_;
  vk::ComputeKernel refitPackKernel_;
  uint32_t taskCapacity_ = 0;
  uint32_t primitiveCount_ = 0;
  std::vector<glm::uvec2> roots_;
  vk::Buffer rootBuffer_;
  vk::Buffer primitives_;
  vk::Buffer nodes_;  // exact bounds: the build's working copy, freed by compact()
  vk::Buffer packedNodes_;
  vk::Buffer frames_;
  vk::Buffer tasks_;  // gpu::BvhBuildCounters, then the tasks of two levels
  BvhBuildStats stats_;
  Refits refits_;
  vk::Buffer keptNodes_;  // the kept tree's exact nodes, as built (recordKeptWithInsertions)
  bool inserted_ = false;
  std::unique_ptr<vk::ComputeKernel> insertKernel_;  // made with the first insertions
  std::unique_ptr<TreeletBuild> treelets_;           // the treelet shape's
};

}  // namespace hmb::passes
