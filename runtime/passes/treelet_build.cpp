#include "runtime/passes/treelet_build.h"

#include <algorithm>
#include <array>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {
namespace {

// kernels/shared/ordered_float.glsl's identities of atomicMin and atomicMax: +inf and -inf.
constexpr uint32_t kOrderedPositiveInfinity = 0xff800000u;
constexpr uint32_t kOrderedNegativeInfinity = 0x007fffffu;

}  // namespace

TreeletBuild::TreeletBuild(const vk::Context& context, std::string name)
    : context_(context),
      name_(std::move(name)),
      boundsKernel_(context, kernels::kernel("bvh/treelet_centroid_bounds")),
      codesKernel_(context, kernels::kernel("bvh/treelet_morton_codes")),
      sortKernel_(context, kernels::kernel("bvh/treelet_sort_pass")),
      hierarchyKernel_(context, kernels::kernel("bvh/treelet_hierarchy")),
      optimizeKernel_(context, kernels::kernel("bvh/treelet_optimize"),
                      std::array<uint32_t, 1>{context.profile().uniformAtomicRounds ? 1u : 0u}),
      packKernel_(context, kernels::kernel("bvh/treelet_pack")) {}

void TreeletBuild::release() { scratch_ = {}; }

void TreeletBuild::record(vk::FrameRecorder& frame, std::string_view pass, const vk::Buffer& boxes,
                          uint32_t primitiveCount, std::span<const glm::uvec2> roots, uint32_t maxLeaf,
                          const TreeletBuildTargets& targets, const std::function<void(vk::FrameRecorder&)>& before,
                          bool byKernel) {
  // Each tree's range cut into tiles of at most HMB_TREELET_TILE places, in tree order.
  const auto treeCount = static_cast<uint32_t>(roots.size());
  std::vector<gpu::TreeletTile> tiles;
  std::vector<gpu::TreeletTree> trees(treeCount);
  for (uint32_t tree = 0; tree < treeCount; ++tree) {
    trees[tree].first = roots[tree].x;
    trees[tree].count = roots[tree].y;
    trees[tree].firstTile = static_cast<uint32_t>(tiles.size());
    for (uint32_t a = 0; a < 4; ++a) {
      trees[tree].centroidLow[a] = kOrderedPositiveInfinity;
      trees[tree].centroidHigh[a] = kOrderedNegativeInfinity;
    }
    for (uint32_t at = 0; at < roots[tree].y; at += HMB_TREELET_TILE)
      tiles.push_back({tree, roots[tree].x + at, std::min(HMB_TREELET_TILE, roots[tree].y - at), 0u});
  }
  const auto tileCount = static_cast<uint32_t>(tiles.size());

  // Scratch grows to what the build needs.
  Scratch& s = scratch_;
  const uint64_t n = std::max(primitiveCount, 1u);
  if (n > s.capacity) {
    s.keys = vk::Buffer(context_, 2 * n * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " codes");
    s.values = vk::Buffer(context_, 2 * n * sizeof(uint32_t), vk::MemoryUse::Device, name_ + " sorted primitives");
    s.nodes = vk::Buffer(context_, 2 * n * sizeof(gpu::TreeletNode), vk::MemoryUse::Device, name_ + " binary tree");
    s.capacity = static_cast<uint32_t>(n);
  }
  if (std::max(tileCount, 1u) > s.tileCapacity) {
    s.tileCapacity = std::max(tileCount, 1u);
    s.tiles = vk::Buffer(context_, s.tileCapacity * sizeof(gpu::TreeletTile), vk::MemoryUse::Device, name_ + " tiles");
    s.digitCounts = vk::Buffer(context_, uint64_t(HMB_TREELET_SORT_PASSES) * s.tileCapacity * HMB_TREELET_DIGITS * 4,
                               vk::MemoryUse::Device, name_ + " digit counts");
  }
  if (treeCount > s.treeCapacity) {
    s.treeCapacity = treeCount;
    s.trees = vk::Buffer(context_, s.treeCapacity * sizeof(gpu::TreeletTree), vk::MemoryUse::Device, name_ + " trees");
  }

  const gpu::TreeletBuildParams params{primitiveCount, treeCount, tileCount, 0u, maxLeaf, 0u, 0u, 0u};
  gpu::BvhBuildCounters counters{};
  counters.nodeCount = treeCount;
  counters.levels = 1;
  frame.write(pass, *targets.counters, std::span<const gpu::BvhBuildCounters>(&counters, 1));
  frame.write(pass, s.trees, std::span<const gpu::TreeletTree>(trees));
  if (tileCount > 0) frame.write(pass, s.tiles, std::span<const gpu::TreeletTile>(tiles));
  frame.fill(pass, s.digitCounts, 0u);
  frame.fill(pass, s.nodes, 0u);
  if (before) before(frame);

  const glm::uvec3 tileGroups = vk::foldedGroups(tileCount);
  std::string stageNames[std::size(kTreeletStages)];
  for (size_t k = 0; k < std::size(kTreeletStages); ++k)
    stageNames[k] = byKernel ? std::string(pass) + "/" + kTreeletStages[k] : std::string(pass);
  const vk::Binding boxesBinding{HMB_TREELET_BINDING_BOXES, &boxes}, tilesBinding{HMB_TREELET_BINDING_TILES, &s.tiles},
      treesBinding{HMB_TREELET_BINDING_TREES, &s.trees}, keysBinding{HMB_TREELET_BINDING_KEYS, &s.keys},
      valuesBinding{HMB_TREELET_BINDING_VALUES, &s.values},
      countsBinding{HMB_TREELET_BINDING_DIGIT_COUNTS, &s.digitCounts},
      nodesBinding{HMB_TREELET_BINDING_NODES, &s.nodes},
      countersBinding{HMB_TREELET_BINDING_COUNTERS, targets.counters};
  frame.dispatch(stageNames[0], boundsKernel_, {boxesBinding, tilesBinding, treesBinding}, params, tileGroups);
  frame.dispatch(stageNames[1], codesKernel_, {boxesBinding, tilesBinding, treesBinding, keysBinding, valuesBinding, countsBinding},
                 params, tileGroups);
  for (uint32_t sortPass = 0; sortPass < HMB_TREELET_SORT_PASSES; ++sortPass) {
    gpu::TreeletBuildParams p = params;
    p.pass = sortPass;
    frame.dispatch(stageNames[2], sortKernel_, {tilesBinding, treesBinding, keysBinding, valuesBinding, countsBinding}, p,
                   tileGroups);
  }
  frame.dispatch(stageNames[3], hierarchyKernel_, {tilesBinding, treesBinding, keysBinding, nodesBinding}, params, tileGroups);
  frame.dispatch(stageNames[4], optimizeKernel_, {boxesBinding, valuesBinding, nodesBinding, treesBinding, countersBinding},
                 params, vk::foldedGroups(vk::groupsFor(primitiveCount, HMB_TREELET_GROUP)));
  frame.dispatch(stageNames[5], packKernel_,
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
