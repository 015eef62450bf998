#include "runtime/passes/bvh_build_pass.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstring>

#include "bvh/packed_node.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/bvh/bvh_build_layout.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

std::vector<gpu::BvhBox> bvhBoxes(std::span<const Aabb> bounds) {
  std::vector<gpu::BvhBox> boxes;
  boxes.reserve(bounds.size());
  for (const Aabb& b : bounds) boxes.push_back({glm::vec4(b.min, 0.0f), glm::vec4(b.max, 0.0f)});
  return boxes;
}

namespace {
// build_level's shared memory besides the per-lane bins: the task's bins and sweeps, and each
// lane's child bounds (kernels/bvh/build_level.comp).
uint64_t levelSharedBytes(const BvhBuildShape& shape) {
  const uint64_t slots = 3ull * HMB_BVH_BINS;
  const uint64_t perLaneBins = shape.laneBins ? shape.levelGroup * slots * 2 * 16 : 32;
  return perLaneBins + slots * (16 + 16 + 8) + 3 * 8 + 16 + shape.levelGroup * 8 * 16 + 8 * 16;
}

std::array<uint32_t, 3> levelSpecialization(const BvhBuildShape& shape) {
  static_assert(HMB_SPEC_BVH_LEVEL_GROUP == 0 && HMB_SPEC_BVH_LANE_BINS == 1 && HMB_SPEC_BVH_LEVEL_SMALL_TASK == 2);
  return {shape.levelGroup, shape.laneBins ? 1u : 0u, shape.smallTask};
}
// begin_build's.
std::array<uint32_t, 1> beginSpecialization(const BvhBuildShape& shape) {
  static_assert(HMB_SPEC_BVH_SMALL_TASK == 0);
  return {shape.smallTask};
}
// build_small_tasks'.
std::array<uint32_t, 2> smallTaskSpecialization(const BvhBuildShape& shape) {
  static_assert(HMB_SPEC_BVH_SMALL_TASK == 0 && HMB_SPEC_BVH_PACK_LATER == 1);
  return {shape.smallTask, shape.packsLater() ? 1u : 0u};
}

// Levels that halving every range takes n primitives down to one in: ceil(log2(n)), as
// kernels/bvh/bvh_build_common.glsl's halvingsToOne.
uint32_t halvingsToOne(uint32_t n) { return static_cast<uint32_t>(std::bit_width(std::max(n, 1u) - 1u)); }

uint32_t largestTreeOf(std::span<const glm::uvec2> roots) {
  uint32_t largest = 0;
  for (const glm::uvec2& root : roots) largest = std::max(largest, root.y);
  return largest;
}
}  // namespace

BvhBuildShape BvhBuildShape::forDevice(const vk::Context& context) {
  BvhBuildShape shape;
  shape.levelGroup = context.profile().bvhLevelGroup;
  shape.laneBins = context.profile().bvhLaneBins;
  shape.treelets = context.profile().treeletMeshBuilds;
  return shape;
}

BvhBuildShape BvhBuildShape::forTopLevel(const vk::Context& context) {
  BvhBuildShape shape = forDevice(context);
  shape.smallTask = context.profile().topLevelSmallTask;
  shape.treelets = false;  // the top level under the GPU profile: passes::LinearBvhPass
  return shape;
}

std::string BvhBuildShape::describe() const {
  if (treelets) return "treelets";
  return std::to_string(levelGroup) + " lanes, " + (laneBins ? "per-lane bins" : "shared atomics") +
         (smallTask == HMB_BVH_SMALL_TASK ? "" : ", small tasks of up to " + std::to_string(smallTask));
}

BvhBuildPass::BvhBuildPass(const vk::Context& context, std::string name, uint32_t maxLeaf)
    : BvhBuildPass(context, std::move(name), maxLeaf, BvhBuildShape::forDevice(context)) {}

BvhBuildPass::BvhBuildPass(const vk::Context& context, std::string name, uint32_t maxLeaf, const BvhBuildShape& shape)
    : context_(context),
      name_(std::move(name)),
      maxLeaf_(maxLeaf),
      shape_(shape),
      beginKernel_(context, kernels::kernel("bvh/begin_build"), beginSpecialization(shape)),
      levelKernel_(context, kernels::kernel("bvh/build_level"), levelSpecialization(shape)),
      sizeDispatchKernel_(context, kernels::kernel("bvh/size_build_dispatch")),
      smallTasksKernel_(context, kernels::kernel("bvh/build_small_tasks"), smallTaskSpecialization(shape)),
      packDeferredKernel_(context, kernels::kernel("bvh/pack_deferred_nodes")),
      refitParentsKernel_(context, kernels::kernel("bvh/refit_parents")),
      refitPlacesKernel_(context, kernels::kernel("bvh/refit_places")),
      refitBoundsKernel_(context, kernels::kernel("bvh/refit_bounds")),
      refitPackKernel_(context, kernels::kernel("bvh/refit_pack")) {
  if (maxLeaf_ == 0) throw Error(name_ + ": a leaf must be able to hold a primitive");
  // A root of HMB_BVH_MAX_TREE_PRIMITIVES must stay under lavapipe's 65535 loop iterations.
  if (shape_.levelGroup < HMB_BVH_LEVEL_GROUP || shape_.levelGroup > context.limits().maxComputeWorkGroupSize[0])
    throw Error(name_ + ": a build workgroup of " + std::to_string(shape_.levelGroup) + " lanes is outside " +
                std::to_string(HMB_BVH_LEVEL_GROUP) + " to the device's " +
                std::to_string(context.limits().maxComputeWorkGroupSize[0]));
  if (levelSharedBytes(shape_) > context.limits().maxComputeSharedMemorySize)
    throw Error(name_ + ": the build's " + shape_.describe() + " need " + std::to_string(levelSharedBytes(shape_)) +
                " bytes of shared memory; the device has " +
                std::to_string(context.limits().maxComputeSharedMemorySize));
  if (shape_.smallTask < HMB_BVH_SMALL_TASK || shape_.smallTask > HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU)
    throw Error(name_ + ": small tasks of up to " + std::to_string(shape_.smallTask) + " primitives are outside " +
                std::to_string(HMB_BVH_SMALL_TASK) + " to " + std::to_string(HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU));
  if (maxLeaf_ > HMB_BVH_PACKED_MAX_COUNT)
    throw Error(name_ + ": a packed leaf holds at most " + std::to_string(HMB_BVH_PACKED_MAX_COUNT) + " primitives");
  if (shape_.treelets) treelets_ = std::make_unique<TreeletBuild>(context, name_);
}

uint32_t BvhBuildPass::smallTaskDepthBound(uint32_t taskPrimitives, bool packsLater,
                                           std::optional<uint32_t> loopBudget) {
  if (!loopBudget) return HMB_BVH_MAX_DEPTH;
  // build_small_tasks' loops over a task of s primitives whose subtree spans L levels: copying
  // in and out (2s), a round per node (2s), two sides per split (2s), each level's primitives
  // binned, partitioned and moved (at most 3s a level); and lavapipe counts one iteration where
  // a loop starts and ends at once: the split's other loops (under 8 a split, 1 a leaf: 9s) and,
  // where the task packs its nodes, the searches of the six bounds each child packs (12 a
  // split: 24s, and more where a bound's guess misses). An eighth of the budget is left for
  // what this count misses (the profile's budget is 7/8 of the driver's): 15s (39s packing) +
  // 3sL <= budget.
  const uint64_t budget = *loopBudget;
  const uint64_t s = std::max(taskPrimitives, 1u), fixed = (packsLater ? 15u : 39u) * s;
  const uint64_t levels = budget > fixed ? (budget - fixed) / (3u * s) : 0u;
  return static_cast<uint32_t>(std::clamp<uint64_t>(levels, 1u, HMB_BVH_MAX_DEPTH + 1u) - 1u);
}

uint32_t BvhBuildPass::depthBound(uint32_t largestTree) const {
  return std::min(maxDepth_, smallTaskDepthBound(std::min(shape_.smallTask, largestTree), shape_.packsLater(),
                                                context_.profile().loopBudget));
}

void BvhBuildPass::reserve(uint32_t primitiveCount, uint32_t treeCount) {
  // A binary tree over n >= 1 primitives has at most 2n - 1 nodes; an empty tree has its root.
  const uint64_t nodes = 2ull * primitiveCount + treeCount;
  // Every task holds two or more primitives of its own, or is a root.
  const uint64_t tasks = std::max<uint64_t>(treeCount, primitiveCount / 2 + 1);
  if (nodes >= HMB_BVH_PACKED_INDEX_LIMIT)
    throw Error(name_ + ": " + std::to_string(primitiveCount) + " primitives are more than one BVH can index");
  // Each buffer grows to what this build needs (an empty build still binds one primitive;
  // compacted buffers are too small for any build's partitions).
  const uint64_t primitiveBytes = 2ull * std::max(primitiveCount, 1u) * sizeof(uint32_t);
  if (primitives_.size() < primitiveBytes)
    primitives_ = vk::Buffer(context_, primitiveBytes, vk::MemoryUse::Device, name_ + " primitives");
  if (nodes_.size() < nodes * sizeof(gpu::BvhNode))
    nodes_ = vk::Buffer(context_, nodes * sizeof(gpu::BvhNode), vk::MemoryUse::Device, name_ + " exact nodes");
  if (packedNodes_.size() < nodes * sizeof(gpu::BvhPackedNode))
    packedNodes_ = vk::Buffer(context_, nodes * sizeof(gpu::BvhPackedNode), vk::MemoryUse::Device, name_ + " nodes");
  if (frames_.size() < treeCount * sizeof(gpu::BvhFrame))
    frames_ = vk::Buffer(context_, treeCount * sizeof(gpu::BvhFrame), vk::MemoryUse::Device, name_ + " frames");
  if (shape_.treelets) {
    // The treelet builder keeps only the counters here, and its own scratch.
    if (tasks_.size() < sizeof(gpu::BvhBuildCounters))
      tasks_ = vk::Buffer(context_, sizeof(gpu::BvhBuildCounters), vk::MemoryUse::Device, name_ + " counters");
  } else if (tasks > taskCapacity_) {
    taskCapacity_ = static_cast<uint32_t>(tasks);
    // The counters at the head, then the two levels' tasks and the small tasks
    // (kernels/bvh/bvh_build_layout.h).
    tasks_ = vk::Buffer(context_, sizeof(gpu::BvhBuildCounters) + 3 * tasks * sizeof(gpu::BvhBuildTask),
                        vk::MemoryUse::Device, name_ + " tasks");
  }
  if (rootBuffer_.size() < treeCount * sizeof(glm::uvec2))
    rootBuffer_ = vk::Buffer(context_, treeCount * sizeof(glm::uvec2), vk::MemoryUse::Device, name_ + " roots");
}

void BvhBuildPass::limitDepth(uint32_t levels) {
  if (levels == 0 || levels > HMB_BVH_MAX_DEPTH)
    throw Error(name_ + ": the depth bound must be 1 to " + std::to_string(HMB_BVH_MAX_DEPTH) +
                " levels (traversal's stack holds no more)");
  if (shape_.treelets && levels + 1 < HMB_TREELET_MAX_HEIGHT)
    throw Error(name_ + ": the treelet builder's trees may be " + std::to_string(HMB_TREELET_MAX_HEIGHT - 1) +
                " levels deep; it takes no tighter bound than that");
  maxDepth_ = levels;
}

uint32_t BvhBuildPass::firstSubmissionLevels(uint32_t largestTree) {
  return std::min(kMaxLevelsPerSubmission, halvingsToOne(largestTree) + kLevelMargin);
}

BvhBuildPass::Start BvhBuildPass::start(const vk::Buffer& boxes, uint32_t primitiveCount,
                                        std::span<const glm::uvec2> roots, uint32_t depthBound) {
  if (roots.empty()) throw Error(name_ + ": a build needs at least one tree");
  for (const glm::uvec2& root : roots) {
    if (uint64_t(root.x) + root.y > primitiveCount)
      throw Error(name_ + ": a tree's primitive range ends past the primitive count");
    if (root.y > HMB_BVH_MAX_TREE_PRIMITIVES)
      throw Error(name_ + ": a tree of " + std::to_string(root.y) + " primitives is more than one tree may hold (" +
                  std::to_string(HMB_BVH_MAX_TREE_PRIMITIVES) + ")");
  }
  const auto treeCount = static_cast<uint32_t>(roots.size());
  reserve(primitiveCount, treeCount);
  primitiveCount_ = primitiveCount;
  roots_.assign(roots.begin(), roots.end());

  Start s;
  s.counters.nodeCount = treeCount;
  s.counters.levels = 1;
  s.rootGroups = vk::foldedGroups(treeCount);
  s.counters.dispatch[0] = glm::uvec4(s.rootGroups, 0u);
  s.counters.dispatch[1] = glm::uvec4(0u, 0u, 1u, 0u);
  s.buffers = buildBindings(boxes);
  s.largestTree = largestTreeOf(roots);
  const uint32_t halvings = halvingsToOne(s.largestTree);
  if (halvings > depthBound)
    throw Error(name_ + ": a tree of " + std::to_string(s.largestTree) + " primitives needs " +
                std::to_string(halvings) + " levels, more than the depth bound of " + std::to_string(depthBound));
  s.params = {primitiveCount, treeCount, taskCapacity_, 0, maxLeaf_, depthBound, 0, 0};
  stats_ = {};
  refits_ = {};  // the old trees' places and order
  inserted_ = false;
  return s;
}

vk::Bindings BvhBuildPass::buildBindings(const vk::Buffer& boxes) const {
  return {{HMB_BUILD_BINDING_BOXES, &boxes},           {HMB_BUILD_BINDING_ROOTS, &rootBuffer_},
          {HMB_BUILD_BINDING_PRIMITIVES, &primitives_}, {HMB_BUILD_BINDING_NODES, &nodes_},
          {HMB_BUILD_BINDING_TASKS, &tasks_},           {HMB_BUILD_BINDING_PACKED_NODES, &packedNodes_},
          {HMB_BUILD_BINDING_FRAMES, &frames_}};
}

const BvhBuildStats& BvhBuildPass::build(vk::FrameRecorder& frame, const vk::Buffer& boxes, uint32_t primitiveCount,
                                         std::span<const glm::uvec2> roots,
                                         const std::function<void(vk::FrameRecorder&)>& before) {
  if (shape_.treelets) {
    start(boxes, primitiveCount, roots, maxDepth_);
    frame.begin();
    recordTreelets(frame, kTreelets, boxes, before, true);
    const vk::FrameTimings timings = frame.submitAndWait();
    readRecordedCounts(timings.frameMilliseconds.value_or(0.0));
    stats_.submissions = 1;
    for (const char* stage : kTreeletStages) {
      const std::string name = std::string(kTreelets) + "/" + stage;
      std::optional<double> sum;
      for (const vk::PassTiming& pass : timings.passes)
        if (pass.name == name && pass.milliseconds) sum = sum.value_or(0.0) + *pass.milliseconds;
      if (sum) stats_.stageMilliseconds.emplace_back(stage, *sum);
    }
    return stats_;
  }
  Start s = start(boxes, primitiveCount, roots, depthBound(largestTreeOf(roots)));
  rootBuffer_.write(std::as_bytes(roots));
  tasks_.write(std::as_bytes(std::span(&s.counters, 1)));
  gpu::BvhBuildCounters& counters = s.counters;
  gpu::BvhBuildParams& params = s.params;
  uint32_t level = 0;
  for (;;) {
    frame.begin();
    if (level == 0) {
      if (before) before(frame);
      frame.dispatch(kBegin, beginKernel_, s.buffers, params, s.rootGroups);
    }
    // Trees of at most shape_.smallTask primitives go to build_small_tasks from begin_build:
    // no level, one sizing of its dispatch.
    const uint32_t end =
        level + (level == 0 ? (allSmall(s.largestTree) ? 0u : firstSubmissionLevels(s.largestTree))
                            : kLevelsPerLaterSubmission);
    if (end == 0) frame.dispatch(kSizeDispatch, sizeDispatchKernel_, s.buffers, params, glm::uvec3(1));
    for (; level < end; ++level) {
      params.level = level;
      frame.dispatchIndirect(kLevel, levelKernel_, s.buffers, params, tasks_,
                             offsetof(gpu::BvhBuildCounters, dispatch) + (level & 1u) * sizeof(glm::uvec4));
      frame.dispatch(kSizeDispatch, sizeDispatchKernel_, s.buffers, params, glm::uvec3(1));
    }
    const vk::FrameTimings timings = frame.submitAndWait();
    for (const vk::PassTiming& pass : timings.passes)
      if (pass.name == kLevel && pass.milliseconds) stats_.levelMilliseconds.push_back(*pass.milliseconds);
    ++stats_.submissions;
    stats_.deviceMilliseconds += timings.frameMilliseconds.value_or(0.0);
    tasks_.read(std::as_writable_bytes(std::span(&counters, 1)));
    if (counters.taskCount[level & 1u] == 0) break;
    if (level > uint64_t(primitiveCount) + 2)
      throw Error(name_ + ": the build did not finish (device fault?)");  // every level splits
  }
  if (counters.smallTaskCount > 0) {
    frame.begin();
    frame.dispatchIndirect(kSmallTasks, smallTasksKernel_, s.buffers, params, tasks_,
                           offsetof(gpu::BvhBuildCounters, smallDispatch));
    recordDeferredPacking(frame, kPackDeferred, s);
    const vk::FrameTimings timings = frame.submitAndWait();
    ++stats_.submissions;
    stats_.deviceMilliseconds += timings.frameMilliseconds.value_or(0.0);
    for (const vk::PassTiming& pass : timings.passes)
      if (pass.name == kSmallTasks) stats_.smallTaskMilliseconds += pass.milliseconds.value_or(0.0);
    tasks_.read(std::as_writable_bytes(std::span(&counters, 1)));
  }
  takeCounts(counters);
  return stats_;
}

uint32_t BvhBuildPass::recordedDepthBound(uint32_t largestTree) const {
  return std::min(depthBound(largestTree), firstSubmissionLevels(largestTree));
}

void BvhBuildPass::record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                          uint32_t primitiveCount, std::span<const glm::uvec2> roots,
                          const std::function<void(vk::FrameRecorder&)>& before) {
  if (shape_.treelets) {
    start(boxes, primitiveCount, roots, maxDepth_);
    recordTreelets(frame, pass, boxes, before);
    return;
  }
  Start s = start(boxes, primitiveCount, roots, recordedDepthBound(largestTreeOf(roots)));
  frame.write(pass, rootBuffer_, roots);
  recordTrees(frame, pass, s, before);
  recordDeferredPacking(frame, pass, s);
}

void BvhBuildPass::recordTreelets(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                                  const std::function<void(vk::FrameRecorder&)>& before, bool byKernel) {
  const TreeletBuildTargets targets{&nodes_, &packedNodes_, &frames_, &primitives_, &tasks_};
  treelets_->record(frame, pass, boxes, primitiveCount_, roots_, maxLeaf_, targets, before, byKernel);
}

void BvhBuildPass::recordTrees(vk::FrameRecorder& frame, std::string_view pass, Start& s,
                               const std::function<void(vk::FrameRecorder&)>& before) {
  const uint32_t depthBound = s.params.maxDepth;
  frame.write(pass, tasks_, std::span<const gpu::BvhBuildCounters>(&s.counters, 1));
  if (before) before(frame);
  frame.dispatch(pass, beginKernel_, s.buffers, s.params, s.rootGroups);
  // A task the levels split holds more than shape_.smallTask primitives, so it needs at least
  // halvingsToOne(shape_.smallTask + 1) more levels below it, and the builder keeps every
  // node within the bound: no such task lies deeper than the bound minus that. The levels
  // down to there finish every tree but the small subtrees they set aside, and those are
  // finished after them. (A root of more than shape_.smallTask primitives is split at level
  // 0 whatever the bound; smaller roots go to the small tasks at once, and where every root is
  // that small no level is recorded, only the sizing of the small tasks' dispatch.)
  const uint32_t belowLargeTask = halvingsToOne(shape_.smallTask + 1u);
  const uint32_t deepestLargeTask = depthBound > belowLargeTask ? depthBound - belowLargeTask : 0u;
  const uint32_t levels = allSmall(s.largestTree) ? 0u : deepestLargeTask + 1u;
  if (levels == 0) frame.dispatch(pass, sizeDispatchKernel_, s.buffers, s.params, glm::uvec3(1));
  for (uint32_t level = 0; level < levels; ++level) {
    s.params.level = level;
    frame.dispatchIndirect(pass, levelKernel_, s.buffers, s.params, tasks_,
                           offsetof(gpu::BvhBuildCounters, dispatch) + (level & 1u) * sizeof(glm::uvec4));
    frame.dispatch(pass, sizeDispatchKernel_, s.buffers, s.params, glm::uvec3(1));
  }
  frame.dispatchIndirect(pass, smallTasksKernel_, s.buffers, s.params, tasks_,
                         offsetof(gpu::BvhBuildCounters, smallDispatch));
}

void BvhBuildPass::recordKeptWithInsertions(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                                            std::span<const uint32_t> order, uint32_t kept,
                                            const std::function<void(vk::FrameRecorder&)>& before) {
  const auto count = static_cast<uint32_t>(order.size());
  if (shape_.treelets) throw Error(name_ + ": a kept tree with insertions is built in levels, not by treelets");
  if (kept == 0 || kept > count) throw Error(name_ + ": a kept tree needs primitives of its own");
  if (count - kept > HMB_BVH_MAX_INSERTED)
    throw Error(name_ + ": " + std::to_string(count - kept) + " insertions, more than " +
                std::to_string(HMB_BVH_MAX_INSERTED));
  const glm::uvec2 root(0u, kept);
  const uint32_t depthBound = recordedDepthBound(kept);
  if (depthBound + (count - kept) > HMB_BVH_MAX_DEPTH)
    throw Error(name_ + ": the insertions could take the kept tree past the depth traversal holds");
  Start s = start(boxes, count, std::span(&root, 1), depthBound);
  s.params.flags = HMB_BVH_BUILD_GIVEN_ORDER;
  frame.write(pass, rootBuffer_, std::span(&root, 1));
  frame.write(pass, primitives_, order);
  recordTrees(frame, pass, s, before);  // its nodes are packed by the insertion, with the others
  const uint64_t keptBytes = (2ull * kept + 1) * sizeof(gpu::BvhNode);
  if (keptNodes_.size() < keptBytes)
    keptNodes_ = vk::Buffer(context_, keptBytes, vk::MemoryUse::Device, name_ + " kept nodes");
  frame.copy(pass, nodes_, keptNodes_, keptBytes);
  inserted_ = true;
  recordInsertions(frame, pass, boxes);
}

void BvhBuildPass::recordInsertionsAgain(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                                         const std::function<void(vk::FrameRecorder&)>& before) {
  if (!inserted_) throw Error(name_ + ": insertions again without a kept tree");
  if (before) before(frame);
  recordInsertions(frame, pass, boxes);
}

void BvhBuildPass::recordInsertions(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes) {
  if (!insertKernel_)
    insertKernel_ = std::make_unique<vk::ComputeKernel>(context_, kernels::kernel("bvh/insert_primitives"));
  vk::Bindings buffers = buildBindings(boxes);
  buffers.push_back({HMB_BUILD_BINDING_KEPT_NODES, &keptNodes_});
  const gpu::BvhBuildParams params{primitiveCount_, 1u, taskCapacity_, 0u, maxLeaf_, maxDepth_, 0u, HMB_BVH_BUILD_GIVEN_ORDER};
  frame.dispatch(pass, *insertKernel_, buffers, params, glm::uvec3(1));
}

void BvhBuildPass::recordDeferredPacking(vk::FrameRecorder& frame, std::string_view pass, const Start& s) {
  if (!shape_.packsLater()) return;
  // Every node the trees may have: 2n - 1 a tree of n, an empty tree its root.
  const uint64_t nodes = 2ull * primitiveCount_ + roots_.size();
  frame.dispatch(pass, packDeferredKernel_, s.buffers, s.params,
                 vk::foldedGroups(vk::groupsFor(static_cast<uint32_t>(nodes), HMB_BVH_PACK_GROUP)));
}

const BvhBuildStats& BvhBuildPass::readRecordedCounts(double deviceMilliseconds) {
  stats_.deviceMilliseconds = deviceMilliseconds;
  gpu::BvhBuildCounters counters{};
  tasks_.read(std::as_writable_bytes(std::span(&counters, 1)));
  takeCounts(counters);
  return stats_;
}

void BvhBuildPass::takeCounts(const gpu::BvhBuildCounters& counters) {
  stats_.smallTasks = counters.smallTaskCount;
  stats_.nodes = counters.nodeCount;
  stats_.leaves = counters.leafCount;
  stats_.levels = counters.levels;
  stats_.levelMilliseconds.resize(std::min<size_t>(stats_.levelMilliseconds.size(), stats_.levels));
}

void BvhBuildPass::prepareRefits(vk::FrameRecorder& frame) {
  const uint64_t nodes = stats_.nodes;
  refits_.roots = vk::uploadedBuffer(context_, roots_, name_ + " refit roots");
  refits_.exact = vk::Buffer(context_, nodes * sizeof(gpu::BvhBox), vk::MemoryUse::Device, name_ + " refit bounds");
  const vk::Buffer parents(context_, nodes * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " refit parents");
  refits_.places = vk::Buffer(context_, nodes * sizeof(glm::uvec2), vk::MemoryUse::Device, name_ + " refit places");
  const gpu::BvhRefitParams params{stats_.nodes, static_cast<uint32_t>(roots_.size()), 0, 0};
  const glm::uvec3 groups = vk::foldedGroups(vk::groupsFor(stats_.nodes, HMB_REFIT_GROUP));
  frame.begin();
  frame.dispatch(kRefitParents, refitParentsKernel_,
                 {{HMB_REFIT_BINDING_ROOTS, &refits_.roots},
                  {HMB_REFIT_BINDING_PACKED_NODES, &packedNodes_},
                  {HMB_REFIT_BINDING_PARENTS, &parents}},
                 params, groups);
  frame.dispatch(kRefitPlaces, refitPlacesKernel_,
                 {{HMB_REFIT_BINDING_PARENTS, &parents}, {HMB_REFIT_BINDING_PLACES, &refits_.places}}, params, groups);
  refits_.preparedMilliseconds = frame.submitAndWait().frameMilliseconds.value_or(0.0);
  refits_.hostPlaces = refits_.places.download<glm::uvec2>();
  refits_.hostPlaces.resize(nodes);
  refits_.trees.clear();
  refits_.depthStart.clear();
}

void BvhBuildPass::sortRefitNodes(std::span<const uint32_t> trees) {
  // The nodes of the trees refitted, by depth, deepest last (a counting sort of their depths):
  // refit_bounds then dispatches over each depth's nodes alone.
  std::vector<uint8_t> refitted(roots_.size(), trees.empty() ? 1 : 0);
  for (const uint32_t tree : trees) {
    if (tree >= roots_.size()) throw Error(name_ + ": refit() of tree " + std::to_string(tree) + ", which does not exist");
    refitted[tree] = 1;
  }
  const std::vector<glm::uvec2>& places = refits_.hostPlaces;
  uint32_t deepest = 0;
  for (const glm::uvec2& place : places)
    if (refitted[place.y]) deepest = std::max(deepest, place.x);
  refits_.depthStart.assign(size_t(deepest) + 2, 0u);
  for (const glm::uvec2& place : places)
    if (refitted[place.y]) ++refits_.depthStart[place.x + 1];
  for (size_t d = 1; d < refits_.depthStart.size(); ++d) refits_.depthStart[d] += refits_.depthStart[d - 1];
  std::vector<uint32_t> order(std::max(refits_.depthStart.back(), 1u)),
      next(refits_.depthStart.begin(), refits_.depthStart.end() - 1);
  for (uint32_t n = 0; n < places.size(); ++n)
    if (refitted[places[n].y]) order[next[places[n].x]++] = n;
  refits_.order = vk::uploadedBuffer(context_, order, name_ + " refit order");
  refits_.trees.assign(trees.begin(), trees.end());
}

double BvhBuildPass::refit(vk::FrameRecorder& frame, const vk::Buffer& boxes, std::span<const uint32_t> trees) {
  const double milliseconds = prepareRefit(frame, trees);
  frame.begin();
  recordRefit(frame, boxes);
  return milliseconds + frame.submitAndWait().frameMilliseconds.value_or(0.0);
}

double BvhBuildPass::prepareRefit(vk::FrameRecorder& frame, std::span<const uint32_t> trees) {
  if (stats_.nodes == 0) throw Error(name_ + ": refit() before a build");
  if (inserted_) throw Error(name_ + ": a tree with insertions is built again, not refitted");
  double milliseconds = 0.0;
  if (refits_.hostPlaces.empty()) {
    prepareRefits(frame);
    milliseconds += refits_.preparedMilliseconds;
  }
  if (refits_.depthStart.empty() || !std::equal(trees.begin(), trees.end(), refits_.trees.begin(), refits_.trees.end()))
    sortRefitNodes(trees);
  return milliseconds;
}

void BvhBuildPass::recordRefit(vk::FrameRecorder& frame, const vk::Buffer& boxes, std::string_view pass) const {
  if (refits_.depthStart.empty()) throw Error(name_ + ": recordRefit() before prepareRefit()");
  if (boxes.size() < uint64_t(primitiveCount_) * sizeof(gpu::BvhBox))
    throw Error(name_ + ": refit() needs a box for each of the " + std::to_string(primitiveCount_) + " primitives");
  gpu::BvhRefitParams params{stats_.nodes, static_cast<uint32_t>(roots_.size()), 0, 0};
  for (size_t depth = refits_.depthStart.size() - 1; depth-- > 0;) {
    params.first = refits_.depthStart[depth];
    params.count = refits_.depthStart[depth + 1] - params.first;
    frame.dispatch(pass.empty() ? kRefitBounds : pass, refitBoundsKernel_,
                   {{HMB_REFIT_BINDING_BOXES, &boxes},
                    {HMB_REFIT_BINDING_ROOTS, &refits_.roots},
                    {HMB_REFIT_BINDING_PRIMITIVES, &primitives_},
                    {HMB_REFIT_BINDING_PACKED_NODES, &packedNodes_},
                    {HMB_REFIT_BINDING_EXACT, &refits_.exact},
                    {HMB_REFIT_BINDING_ORDER, &refits_.order}},
                   params, vk::foldedGroups(vk::groupsFor(params.count, HMB_REFIT_GROUP)));
  }
  params.first = 0;
  params.count = refits_.depthStart.back();
  frame.dispatch(pass.empty() ? kRefitPack : pass, refitPackKernel_,
                 {{HMB_REFIT_BINDING_ROOTS, &refits_.roots},
                  {HMB_REFIT_BINDING_PACKED_NODES, &packedNodes_},
                  {HMB_REFIT_BINDING_FRAMES, &frames_},
                  {HMB_REFIT_BINDING_EXACT, &refits_.exact},
                  {HMB_REFIT_BINDING_PLACES, &refits_.places},
                  {HMB_REFIT_BINDING_ORDER, &refits_.order}},
                 params, vk::foldedGroups(vk::groupsFor(params.count, HMB_REFIT_GROUP)));
}

void BvhBuildPass::compact(vk::FrameRecorder& frame) {
  if (stats_.nodes == 0) throw Error(name_ + ": compact() before a build");
  if (inserted_) throw Error(name_ + ": a tree with insertions is built again, not compacted");
  // The scratch goes first, so the copies below add less to the peak: the tasks, and the
  // exact nodes, which only the build reads.
  tasks_ = {};
  rootBuffer_ = {};
  nodes_ = {};
  if (treelets_) treelets_->release();
  taskCapacity_ = 0;
  const uint64_t nodeBytes = uint64_t(stats_.nodes) * sizeof(gpu::BvhPackedNode);
  const uint64_t primitiveBytes = uint64_t(std::max(primitiveCount_, 1u)) * sizeof(uint32_t);
  vk::Buffer nodes(context_, nodeBytes, vk::MemoryUse::Device, name_ + " nodes");
  vk::Buffer primitives(context_, primitiveBytes, vk::MemoryUse::Device, name_ + " primitives");
  const uint64_t frameBytes = roots_.size() * sizeof(gpu::BvhFrame);
  vk::Buffer frames(context_, frameBytes, vk::MemoryUse::Device, name_ + " frames");
  frame.begin();
  frame.copy(kCompact, packedNodes_, nodes, nodeBytes);
  frame.copy(kCompact, primitives_, primitives, primitiveBytes);
  frame.copy(kCompact, frames_, frames, frameBytes);
  stats_.deviceMilliseconds += frame.submitAndWait().frameMilliseconds.value_or(0.0);
  packedNodes_ = std::move(nodes);
  primitives_ = std::move(primitives);
  frames_ = std::move(frames);
}

uint64_t BvhBuildPass::usedTreeBytes() const {
  return uint64_t(stats_.nodes) * sizeof(gpu::BvhPackedNode) +
         uint64_t(primitiveCount_) * sizeof(uint32_t) + roots_.size() * sizeof(gpu::BvhFrame);
}

std::vector<gpu::BvhNode> BvhBuildPass::downloadNodes() const {
  const std::vector<gpu::BvhPackedNode> packed = packedNodes_.download<gpu::BvhPackedNode>();
  const std::vector<gpu::BvhFrame> frames = frames_.download<gpu::BvhFrame>();
  std::vector<gpu::BvhNode> nodes(stats_.nodes);
  // A node unpacks in its tree's frame: walk each tree from its root (an empty tree's root
  // has no children, whatever its index word says; one with insertions has).
  uint32_t visited = 0;
  for (uint32_t tree = 0; tree < roots_.size(); ++tree) {
    std::vector<uint32_t> stack{tree};
    while (!stack.empty()) {
      const uint32_t index = stack.back();
      stack.pop_back();
      const gpu::BvhNode node = bvh::unpackNode(packed.at(index), frames.at(tree));
      if (++visited > nodes.size())  // a child index pointing back up: nodes left unwritten
        throw Error(name_ + ": the built nodes do not form trees (a node is reached twice)");
      nodes.at(index) = node;
      if (node.count == 0 && (inserted_ || roots_[tree].y > 1))
        stack.insert(stack.end(), {node.leftOrFirst, node.leftOrFirst + 1});
    }
  }
  return nodes;
}

bvh::Bvh BvhBuildPass::download(uint32_t root) const {
  if (root >= roots_.size()) throw Error(name_ + ": no tree " + std::to_string(root));
  const std::vector<gpu::BvhNode> nodes = downloadNodes();
  const std::vector<uint32_t> primitives = primitives_.download<uint32_t>();
  // With insertions, the tree holds every place of the order.
  const glm::uvec2 range = inserted_ ? glm::uvec2(0u, primitiveCount_) : roots_[root];
  bvh::Bvh out;
  if (range.y == 0) return out;
  // Breadth-first copy keeps siblings adjacent, as the layout requires.
  out.nodes.push_back(nodes.at(root));
  for (size_t i = 0; i < out.nodes.size(); ++i) {
    bvh::Node& node = out.nodes[i];
    if (bvh::isLeaf(node)) {
      const uint32_t first = static_cast<uint32_t>(out.primitiveIndices.size());
      for (uint32_t k = 0; k < node.count; ++k)
        out.primitiveIndices.push_back(primitives.at(node.leftOrFirst + k) - range.x);
      node.leftOrFirst = first;
      continue;
    }
    const uint32_t left = node.leftOrFirst;
    node.leftOrFirst = static_cast<uint32_t>(out.nodes.size());
    const gpu::BvhNode l = nodes.at(left), r = nodes.at(left + 1);  // copies: push_back may move `node`
    out.nodes.push_back(l);
    out.nodes.push_back(r);
  }
  return out;
}

}  // namespace hmb::passes
