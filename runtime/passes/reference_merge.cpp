#include "runtime/passes/reference_merge.h"

#include <algorithm>
#include <map>
#include <string>
#include <utility>

#include "hmblur/error.h"
#include "runtime/passes/reference_stage.h"

namespace hmb::passes {
namespace {

// The first setting in which two parts' renders differ, as "spp 64 against 256": the scene, the
// size, the samples and the seed first, then the rest.
std::string firstDifference(const nlohmann::json& a, const nlohmann::json& b) {
  for (const char* key : {"scene", "width", "height", "spp", "seed"})
    if (a.contains(key) && b.contains(key) && a.at(key) != b.at(key))
      return std::string(key) + " " + b.at(key).dump() + " against " + a.at(key).dump();
  for (const auto& [key, value] : a.items())
    if (!b.contains(key) || b.at(key) != value)
      return key + " " + (b.contains(key) ? b.at(key).dump() : "missing") + " against " + value.dump();
  for (const auto& [key, value] : b.items())
    if (!a.contains(key)) return key + " " + value.dump() + " against missing";
  return "none";
}

}  // namespace

MergedReference mergeReferenceParts(const vk::Context& context, vk::FrameRecorder& frame,
                                    const std::vector<std::filesystem::path>& paths, bool allowPartial) {
  if (paths.empty()) throw Error("no parts to merge");
  MergedReference merged;
  for (const std::filesystem::path& path : paths) merged.parts.push_back(readReferencePartial(path));
  const auto name = [&](size_t i) { return "'" + paths[i].string() + "'"; };
  const ReferencePartial& first = merged.parts.front();
  std::map<uint32_t, size_t> byShard;
  for (size_t i = 0; i < merged.parts.size(); ++i) {
    const ReferencePartial& part = merged.parts[i];
    if (part.version != first.version)
      throw Error(name(i) + " was written by " + part.version + ", " + name(0) + " by " + first.version +
                  ": merge the parts of one version");
    if (part.identity != first.identity)
      throw Error(name(i) + " is of another render than " + name(0) + ": " +
                  firstDifference(first.identity, part.identity));
    if (part.shardCount != first.shardCount || part.samples != first.samples || part.pixels != first.pixels)
      throw Error(name(i) + " is shard " + part.shardText() + ", " + name(0) + " shard " + first.shardText() +
                  ": merge the parts of one split");
    if (const auto [at, added] = byShard.emplace(part.shardIndex, i); !added)
      throw Error("shard " + part.shardText() + " is given twice: " + name(at->second) + " and " + name(i));
    if (!part.finished() && !allowPartial)
      throw Error(name(i) + " holds shard " + part.shardText() + " unfinished (" + std::to_string(part.samplesDone) +
                  " of " + std::to_string(part.shard.size()) +
                  " samples): run its render again to finish it, or merge with --allow-partial");
  }
  for (uint32_t shard = 0; shard < first.shardCount; ++shard)
    if (!byShard.count(shard)) merged.missingShards.push_back(shard);
  if (!merged.missingShards.empty() && !allowPartial) {
    std::string missing;
    for (const uint32_t shard : merged.missingShards)
      missing += (missing.empty() ? "" : ", ") + std::to_string(shard) + "/" + std::to_string(first.shardCount);
    throw Error("shard" + std::string(merged.missingShards.size() > 1 ? "s " : " ") + missing +
                (merged.missingShards.size() > 1 ? " are" : " is") +
                " missing (--allow-partial merges the samples the parts hold)");
  }
  try {
    merged.width = first.identity.at("width").get<uint32_t>();
    merged.height = first.identity.at("height").get<uint32_t>();
  } catch (const std::exception&) {
    throw Error(name(0) + " is damaged: its header has no image size");
  }
  if (uint64_t(merged.width) * merged.height != first.pixels)
    throw Error(name(0) + " is damaged: its size and pixel count disagree");
  merged.samples = first.samples;

  // Every node of every part in sample order (sample 0 first), and where its sums lie.
  struct Source {
    SumNode node;
    size_t part;
    size_t index;
  };
  std::vector<Source> sources;
  for (size_t i = 0; i < merged.parts.size(); ++i) {
    const ReferencePartial& part = merged.parts[i];
    merged.samplesHeld += part.samplesDone;
    for (size_t n = 0; n < part.nodes.size(); ++n) sources.push_back({part.nodes[n], i, n});
  }
  std::sort(sources.begin(), sources.end(),
            [](const Source& a, const Source& b) { return a.node.firstSampleIndex() < b.node.firstSampleIndex(); });

  const vk::Buffer color(context, first.pixels * sizeof(glm::vec4), vk::MemoryUse::Device, "merged reference");
  const ReferenceSumKernels kernels(context);
  DeviceSumSlots slots(context, frame, kernels, merged.width, merged.height, merged.timings);
  SumStack stack(slots);
  for (const Source& source : sources) {
    std::vector<glm::vec4> sums(first.pixels);
    readReferencePartialNode(paths[source.part], merged.parts[source.part], source.index, sums);
    stack.push(source.node, std::move(sums), true);
  }
  slots.average(stack.total(), color);
  merged.color = color.download<glm::vec4>();
  return merged;
}

}  // namespace hmb::passes
