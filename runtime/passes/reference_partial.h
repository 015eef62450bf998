// A reference render's sums on disk: its checkpoint while it runs, and, for a shard, what it
// hands to the merge (hmblur merge). One format for both, so a shard is checkpointed and resumed
// like any render. The file: 8 bytes "HMBREF2\0", the header's length in bytes (uint64, little
// endian), the header (JSON: what render it belongs to, which shard, how far it got, which tree
// nodes follow), then each node's sums in the header's order: one vec4 per pixel, row 0 at the
// top, rgb the sum of the node's samples and w their count.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "runtime/passes/reference_sum_tree.h"

namespace hmb::passes {

struct ReferencePartial {
  // Every input that decides a sample's value: the scene, the image size, the render's sample
  // count and every setting that chooses its samples. Parts merge only when theirs are equal.
  nlohmann::json identity;
  std::string version;  // the hmblur version and revision that rendered it
  uint32_t samples = 0;     // N, of the whole render
  uint32_t shardIndex = 0;  // 0-based
  uint32_t shardCount = 1;
  SampleRange shard;         // the samples of the shard
  uint32_t samplesDone = 0;  // the shard's, counted from its first
  uint64_t pixels = 0;
  std::vector<SumNode> nodes;  // the nodes whose sums follow, in order

  bool finished() const { return samplesDone == shard.size(); }
  std::string shardText() const { return std::to_string(shardIndex) + "/" + std::to_string(shardCount); }
};

// The version a partial written now records.
std::string referencePartialVersion();

// Reads and checks the header (not the sums): its shard and nodes are those of a shard of its
// render. Throws hmb::Error in one line naming the file: missing, not a reference partial, of
// another format, damaged, or shorter than its header says.
ReferencePartial readReferencePartial(const std::filesystem::path& path);

// Reads the sums of node `index` of the header into `sums` (one per pixel).
void readReferencePartialNode(const std::filesystem::path& path, const ReferencePartial& header, size_t index,
                              std::span<glm::vec4> sums);

// Writes the header and then, for each node in order, the sums `nodeSums(i)` gives (one per
// pixel). Written beside the target and renamed over it, so an interrupted write never loses
// the last whole file.
void writeReferencePartial(const std::filesystem::path& path, const ReferencePartial& header,
                           const std::function<std::vector<glm::vec4>(size_t)>& nodeSums);

}  // namespace hmb::passes
