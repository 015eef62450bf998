#include "hmblur/reference_settings.h"

#include <charconv>
#include <string>

#include "hmblur/error.h"

namespace hmb::passes {
namespace {

constexpr uint32_t kMaxSamplesPerPixel = 1u << 20;

std::string shardText(const ReferenceShard& shard) {
  return std::to_string(shard.index) + "/" + std::to_string(shard.count);
}

// "I/K": shard I (0-based) of K.
ReferenceShard parseShard(std::string_view text) {
  const size_t slash = text.find('/');
  ReferenceShard shard;
  const auto read = [](std::string_view part, uint32_t& value) {
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
    return !part.empty() && error == std::errc() && end == part.data() + part.size();
  };
  if (slash == std::string_view::npos || !read(text.substr(0, slash), shard.index) ||
      !read(text.substr(slash + 1), shard.count))
    throw Error("--shard '" + std::string(text) + "' is not I/K (shard I of K, I from 0)");
  return shard;
}

settings::Setting<ReferenceSettings, ReferenceSettings> shardSetting() {
  using S = ReferenceSettings;
  settings::Setting<S, S> s{"shard", "reference",
                            "render shard I of K of the samples (I from 0) into a part for hmblur merge: with "
                            "--shard, --out names the part (.hmbpart), which is also the shard's checkpoint",
                            "", "I/K, I < K <= spp", "I/K"};
  s.read = [](S& c, std::string_view text) { c.shard = parseShard(text); };
  s.apply = [](const S& c, S& settings) { settings.shard = c.shard; };
  s.problem = [](const S& settings) -> std::string {
    const ReferenceShard& shard = settings.shard;
    if (shard.count == 0 || shard.index >= shard.count)
      return "shard " + shardText(shard) + ": I must be below K";
    if (shard.count > settings.samplesPerPixel)
      return "shard " + shardText(shard) + ": " + std::to_string(shard.count) + " shards of " +
             std::to_string(settings.samplesPerPixel) + " samples per pixel would leave some empty";
    return {};
  };
  s.show = [](const S& settings) { return shardText(settings.shard); };
  s.defaultText = "0/1, the whole render";
  return s;
}

}  // namespace

const settings::Table<ReferenceSettings, ReferenceSettings>& referenceSettingTable() {
  using namespace settings;
  using S = ReferenceSettings;
  static const Table<S, S> table = {
      number("spp", "reference", "samples (shutter times) per pixel", &S::samplesPerPixel, &S::samplesPerPixel,
             Range<uint32_t>{1, kMaxSamplesPerPixel}),
      number("seed", "reference", "seed of the shutter times' and pixel positions' jitter", &S::seed, &S::seed,
             Range<uint32_t>{}),
      flag("pixel-jitter", "reference", "a random point in the pixel per sample instead of its centre",
           &S::pixelJitter, &S::pixelJitter),
      path("checkpoint", "reference", "file to resume from and to save the sum to after every batch", &S::checkpoint,
           &S::checkpoint),
      shardSetting(),
  };
  return table;
}

void validateReferenceSettings(const ReferenceSettings& settings) {
  settings::checkAll(referenceSettingTable(), settings, "reference settings");
  if (settings.timesPerBatch == 0 || settings.timesPerBatch > 4096)
    throw Error("reference batch of " + std::to_string(settings.timesPerBatch) + " times is out of range 1..4096");
  if (settings.shard.count > 1 && settings.checkpoint.empty())
    throw Error("a shard of the reference keeps its sums in a file for the merge: give it a checkpoint");
  if (!settings.checkpoint.empty()) {
    const std::filesystem::path parent = settings.checkpoint.parent_path();
    if (!parent.empty() && !std::filesystem::is_directory(parent))
      throw Error("--checkpoint '" + settings.checkpoint.string() + "': directory '" + parent.string() +
                  "' does not exist");
  }
}

}  // namespace hmb::passes
