#include "runtime/passes/reference_partial.h"

#include <cstring>
#include <fstream>

#include "hmblur/error.h"
#include "hmblur/system_info.h"

namespace hmb::passes {
namespace {

constexpr char kMagic[8] = {'H', 'M', 'B', 'R', 'E', 'F', '2', '\0'};
constexpr char kOlderMagic[8] = {'H', 'M', 'B', 'R', 'E', 'F', '1', '\0'};
constexpr uint64_t kMaxHeaderBytes = 1u << 20;
constexpr uint64_t kHeaderStart = sizeof(kMagic) + sizeof(uint64_t);

nlohmann::json nodeJson(const SumNode& node) {
  if (node.isFirstSample()) return {{"sample", 0}};
  return {{"level", node.level}, {"start", node.start}};
}

SumNode nodeFromJson(const nlohmann::json& j) {
  if (j.contains("sample")) return SumNode::firstSample();
  return {j.at("level").get<uint32_t>(), j.at("start").get<uint32_t>()};
}

uint64_t nodeBytes(const ReferencePartial& header) { return header.pixels * sizeof(glm::vec4); }

}  // namespace

std::string referencePartialVersion() {
  const SystemInfo info = querySystemInfo();
  return "hmblur " + info.version + " (" + info.gitRevision + ")";
}

ReferencePartial readReferencePartial(const std::filesystem::path& path) {
  const std::string name = std::string("'").append(path.string()).append("'");
  std::error_code error;
  const uintmax_t fileBytes = std::filesystem::file_size(path, error);
  if (error) throw Error(name + " cannot be read: " + error.message());
  std::ifstream in(path, std::ios::binary);
  char magic[8] = {};
  uint64_t headerBytes = 0;
  in.read(magic, sizeof(magic));
  in.read(reinterpret_cast<char*>(&headerBytes), sizeof(headerBytes));
  if (in && std::memcmp(magic, kOlderMagic, sizeof(magic)) == 0)
    throw Error(name + " is a reference checkpoint of an older hmblur (format 1): render it again");
  if (!in || std::memcmp(magic, kMagic, sizeof(magic)) != 0)
    throw Error(name + " is not a reference partial or checkpoint");
  if (headerBytes > kMaxHeaderBytes || kHeaderStart + headerBytes > fileBytes) throw Error(name + " is truncated");
  std::string text(headerBytes, '\0');
  in.read(text.data(), static_cast<std::streamsize>(headerBytes));
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  ReferencePartial header;
  try {
    if (!in || j.is_discarded()) throw Error("");
    header.identity = j.at("identity");
    header.version = j.at("version").get<std::string>();
    header.samples = j.at("samples").get<uint32_t>();
    header.shardIndex = j.at("shard").at("index").get<uint32_t>();
    header.shardCount = j.at("shard").at("count").get<uint32_t>();
    header.shard = {j.at("shard").at("first_sample").get<uint32_t>(), j.at("shard").at("end_sample").get<uint32_t>()};
    header.samplesDone = j.at("samples_done").get<uint32_t>();
    header.pixels = j.at("pixels").get<uint64_t>();
    for (const nlohmann::json& node : j.at("nodes")) header.nodes.push_back(nodeFromJson(node));
  } catch (const std::exception&) {
    throw Error(name + " is damaged: its header is not a reference partial's");
  }
  // At most two nodes a level of a tree of 32 levels, and sample 0.
  const bool consistent = header.pixels > 0 && header.pixels <= (uint64_t(1) << 32) && header.nodes.size() <= 65 &&
                          header.shardCount > 0 && header.shardIndex < header.shardCount &&
                          header.shardCount <= header.samples &&
                          shardSamples(header.samples, header.shardIndex, header.shardCount).begin == header.shard.begin &&
                          shardSamples(header.samples, header.shardIndex, header.shardCount).end == header.shard.end &&
                          header.samplesDone <= header.shard.size();
  if (!consistent) throw Error(name + " is damaged: its shard does not add up");
  if (header.nodes != heldNodes(header.shard, header.samplesDone))
    throw Error(name + " is damaged: its nodes are not those of its " + std::to_string(header.samplesDone) +
                " samples");
  const uint64_t expected = kHeaderStart + headerBytes + header.nodes.size() * nodeBytes(header);
  if (fileBytes < expected)
    throw Error(name + " is truncated: " + std::to_string(fileBytes) + " bytes of " + std::to_string(expected));
  if (fileBytes > expected)
    throw Error(name + " is damaged: " + std::to_string(fileBytes - expected) + " bytes past its last node");
  return header;
}

void readReferencePartialNode(const std::filesystem::path& path, const ReferencePartial& header, size_t index,
                              std::span<glm::vec4> sums) {
  std::ifstream in(path, std::ios::binary);
  uint64_t headerBytes = 0;
  in.seekg(sizeof(kMagic));
  in.read(reinterpret_cast<char*>(&headerBytes), sizeof(headerBytes));
  in.seekg(static_cast<std::streamoff>(kHeaderStart + headerBytes + index * nodeBytes(header)));
  in.read(reinterpret_cast<char*>(sums.data()), static_cast<std::streamsize>(sums.size_bytes()));
  if (!in || sums.size() != header.pixels) throw Error("'" + path.string() + "' is truncated");
}

void writeReferencePartial(const std::filesystem::path& path, const ReferencePartial& header,
                           const std::function<std::vector<glm::vec4>(size_t)>& nodeSums) {
  nlohmann::json nodes = nlohmann::json::array();
  for (const SumNode& node : header.nodes) nodes.push_back(nodeJson(node));
  const std::string text = nlohmann::json{{"identity", header.identity},
                                          {"version", header.version},
                                          {"samples", header.samples},
                                          {"shard",
                                           {{"index", header.shardIndex},
                                            {"count", header.shardCount},
                                            {"first_sample", header.shard.begin},
                                            {"end_sample", header.shard.end}}},
                                          {"samples_done", header.samplesDone},
                                          {"pixels", header.pixels},
                                          {"nodes", nodes}}
                               .dump();
  const uint64_t headerBytes = text.size();
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(kMagic, sizeof(kMagic));
    out.write(reinterpret_cast<const char*>(&headerBytes), sizeof(headerBytes));
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    for (size_t i = 0; i < header.nodes.size(); ++i) {
      const std::vector<glm::vec4> sums = nodeSums(i);
      if (sums.size() != header.pixels) throw Error("reference partial: node sums of the wrong size");
      out.write(reinterpret_cast<const char*>(sums.data()), static_cast<std::streamsize>(nodeBytes(header)));
    }
    if (!out) throw Error("cannot write '" + partial.string() + "'");
  }
  std::filesystem::rename(partial, path);
}

}  // namespace hmb::passes
