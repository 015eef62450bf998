#include "runtime/passes/treelet_build.h"

#include <algorithm>
#include <array>

#include "runtime/error.h"
#include "runtime/vulkan/context.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {
namespace {

// kernels/shared/ordered_float.glsl's identities of atomicMin and atomicMax: +inf and -inf.
constexpr uint32_t kOrderedPositiveInfinity = 0xff800000u;
constexpr uint32_t kOrderedNegativeInfinity = 0x007fffffu;

}  // namespace

std::vector<gpu::TreeletTile> treeletTiles(std::span<const glm::uvec2> roots) {
  std::vector<gpu::TreeletTile> tiles;
  for (uint32_t tree = 0; tree < roots.size(); ++tree)
    for (uint32_t at = 0; at < roots[tree].y; at += HMB_TREELET_TILE)
      tiles.push_back({tree, roots[tree].x + at, std::min(HMB_TREELET_TILE, roots[tree].y - at), 0u});
  return tiles;
}

TreeletBuild::TreeletBuild(const vk::Context& context, std::string name)
    : context_(context),
      name_(std::move(name)),
      boundsKernel_(context, "bvh/treelet_centroid_bounds", sizeof(gpu::TreeletBuildParams)),
      codesKernel_(context, "bvh/treelet_morton_codes", sizeof(gpu::TreeletBuildParams)),
      sortKernel_(context, "bvh/treelet_sort_pass", sizeof(gpu::TreeletBuildParams)),
      hierarchyKernel_(context, "bvh/treelet_hierarchy", sizeof(gpu::TreeletBuildParams)),
      optimizeKernel_(context, "bvh/treelet_optimize", sizeof(gpu::TreeletBuildParams),
                      std::array<uint32_t, 1>{context.profile().uniformAtomicRounds ? 1u : 0u}),
      packKernel_(context, "bvh/treelet_pack", sizeof(gpu::TreeletBuildParams)) {}

void TreeletBuild::release() {
  tiles_ = {};
  trees_ = {};
  keys_ = {};
  values_ = {};
  digitCounts_ = {};
  nodes_ = {};
  capacity_ = tileCapacity_ = treeCapacity_ = 0;
}

uint64_t TreeletBuild::scratchBytes() const {
  return tiles_.size() + trees_.size() + keys_.size() + values_.size() + digitCounts_.size() + nodes_.size();
}

void TreeletBuild::record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                          uint32_t primitiveCount, std::span<const glm::uvec2> roots, uint32_t maxLeaf,
                          const TreeletBuildTargets& targets, const std::function<void(vk::FrameRecorder&)>& before) {
  const auto treeCount = static_cast<uint32_t>(roots.size());
  const std::vector<gpu::TreeletTile> tiles = treeletTiles(roots);
  const auto tileCount = static_cast<uint32_t>(tiles.size());
  std::vector<gpu::TreeletTree> trees(treeCount);
  for (uint32_t tree = 0, tile = 0; tree < treeCount; ++tree) {
    trees[tree].first = roots[tree].x;
    trees[tree].count = roots[tree].y;
    trees[tree].firstTile = tile;
    for (uint32_t a = 0; a < 4; ++a) {
      trees[tree].centroidLow[a] = kOrderedPositiveInfinity;
      trees[tree].centroidHigh[a] = kOrderedNegativeInfinity;
    }
    tile += (roots[tree].y + HMB_TREELET_TILE - 1) / HMB_TREELET_TILE;
  }

  // Scratch grows to what the build needs.
  const uint64_t n = std::max(primitiveCount, 1u);
  if (n > capacity_) {
    keys_ = vk::Buffer(context_, 2 * n * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " codes");
    values_ = vk::Buffer(context_, 2 * n * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " sorted primitives");
    nodes_ = vk::Buffer(context_, 2 * n * sizeof(gpu::TreeletNode), vk::MemoryUse::Device, name_ + " binary tree");
    capacity_ = static_cast<uint32_t>(n);
  }
  if (std::max(tileCount, 1u) > tileCapacity_) {
    tileCapacity_ = std::max(tileCount, 1u);
    tiles_ = vk::Buffer(context_, tileCapacity_ * sizeof(gpu::TreeletTile), vk::MemoryUse::Device, name_ + " tiles");
    digitCounts_ = vk::Buffer(context_, uint64_t(HMB_TREELET_SORT_PASSES) * tileCapacity_ * HMB_TREELET_DIGITS * 4,
                              vk::MemoryUse::Device, name_ + " digit counts");
  }
  if (treeCount > treeCapacity_) {
    treeCapacity_ = treeCount;
    trees_ = vk::Buffer(context_, treeCapacity_ * sizeof(gpu::TreeletTree), vk::MemoryUse::Device, name_ + " trees");
  }

  const gpu::TreeletBuildParams params{primitiveCount, treeCount, tileCount, 0u, maxLeaf, 0u, 0u, 0u};
  gpu::BvhBuildCounters counters{};
  counters.nodeCount = treeCount;
  counters.levels = 1;
  frame.write(pass, *targets.counters, std::span<const gpu::BvhBuildCounters>(&counters, 1));
  frame.write(pass, trees_, std::span<const gpu::TreeletTree>(trees));
  if (tileCount > 0) frame.write(pass, tiles_, std::span<const gpu::TreeletTile>(tiles));
  frame.fill(pass, digitCounts_, 0u);
  frame.fill(pass, nodes_, 0u);
  if (before) before(frame);

  const glm::uvec3 tileGroups = vk::foldedGroups(tileCount);
  const vk::Binding boxesBinding{HMB_TREELET_BINDING_BOXES, &boxes}, tilesBinding{HMB_TREELET_BINDING_TILES, &tiles_},
      treesBinding{HMB_TREELET_BINDING_TREES, &trees_}, keysBinding{HMB_TREELET_BINDING_KEYS, &keys_},
      valuesBinding{HMB_TREELET_BINDING_VALUES, &values_},
      countsBinding{HMB_TREELET_BINDING_DIGIT_COUNTS, &digitCounts_},
      nodesBinding{HMB_TREELET_BINDING_NODES, &nodes_},
      countersBinding{HMB_TREELET_BINDING_COUNTERS, targets.counters};
  frame.dispatch(pass, boundsKernel_, {boxesBinding, tilesBinding, treesBinding}, params, tileGroups);
  frame.dispatch(pass, codesKernel_, {boxesBinding, tilesBinding, treesBinding, keysBinding, valuesBinding, countsBinding},
                 params, tileGroups);
  for (uint32_t sortPass = 0; sortPass < HMB_TREELET_SORT_PASSES; ++sortPass) {
    gpu::TreeletBuildParams p = params;
    p.pass = sortPass;
    frame.dispatch(pass, sortKernel_, {tilesBinding, treesBinding, keysBinding, valuesBinding, countsBinding}, p,
                   tileGroups);
  }
  frame.dispatch(pass, hierarchyKernel_, {tilesBinding, treesBinding, keysBinding, nodesBinding}, params, tileGroups);
  frame.dispatch(pass, optimizeKernel_, {boxesBinding, valuesBinding, nodesBinding, treesBinding, countersBinding},
                 params, vk::foldedGroups(vk::groupsFor(primitiveCount, HMB_TREELET_GROUP)));
  frame.dispatch(pass, packKernel_,
                 {nodesBinding,
                  treesBinding,
                  valuesBinding,
                  countersBinding,
                  {HMB_TREELET_BINDING_EXACT_NODES, targets.exactNodes},
                  {HMB_TREELET_BINDING_PACKED_NODES, targets.packedNodes},
                  {HMB_TREELET_BINDING_FRAMES, targets.frames},
                  {HMB_TREELET_BINDING_PRIMITIVES, targets.primitives}},
                 params, vk::foldedGroups(vk::groupsFor(2 * primitiveCount + treeCount, HMB_TREELET_GROUP)));
}

}  // namespace hmb::passes
