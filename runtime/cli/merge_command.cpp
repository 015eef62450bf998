#include "runtime/cli/merge_command.h"

#include <chrono>
#include <filesystem>
#include <iostream>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/report.h"
#include "hmblur/system_info.h"
#include "runtime/cli/output_paths.h"
#include "runtime/io/image_files.h"
#include "runtime/methods/raster_frame.h"
#include "runtime/passes/reference_merge.h"

namespace hmb::cli {

CLI::App* addMergeCommand(CLI::App& app, MergeOptions& options) {
  CLI::App* command = app.add_subcommand(
      "merge", "Join the parts of a reference render split into shards into the image of the whole render, bit for bit");
  command->footer(R"(Sharding a reference across machines (docs/sharded-reference.md):
  hmblur render --scene S --method reference --spp N --shard I/K --out part-I.hmbpart   (I = 0 .. K-1)
  hmblur merge part-*.hmbpart --out reference.exr
Shard I takes a run of consecutive samples of the N, with the shutter times and pixel
jitter one render of N spp gives them. Its part keeps its sums as nodes of a fixed tree of
pairwise sums (at most 2 log2(N) + 1 images of 16 bytes a pixel), so the merge adds them in
the order one render does: the same bits, in whatever order the parts come, where every
shard ran on the same device and driver (lavapipe's results also depend on the CPU's FMA).
A part is also its shard's checkpoint: the same command again resumes it.
Slurm, one array task a shard and a merge after them (scripts/slurm/):
  JOB=$(sbatch --parsable --array=0-3 --export=ALL,SHARDS=4,SPP=1024 scripts/slurm/reference-array.sbatch)
  sbatch --dependency=afterok:$JOB --export=ALL,SHARDS=4,SPP=1024 scripts/slurm/reference-merge.sbatch
GNU parallel over ssh hosts (hmblur on each host's PATH):
  parallel -S host1,host2 --workdir . --return part-{}.hmbpart --cleanup \
    hmblur --quiet render --scene bistro --method reference --spp 1024 --shard {}/4 --out part-{}.hmbpart ::: 0 1 2 3
  hmblur merge part-*.hmbpart --out reference.exr
Frames of a sequence (render --frames) need no merge: give each machine its own frames.)");
  command->add_option("parts", options.parts, "The shards' parts (.hmbpart), in any order")->required();
  command->add_option("--out", options.out, "The merged image (.exr, as render --out writes)")->required();
  command->add_option("--report", options.report,
                      "JSON report: the render the parts belong to, each part, the samples merged, device times");
  command->add_flag("--allow-partial", options.allowPartial,
                    "Merge what the parts hold when shards are missing or unfinished (said on stderr): the mean of "
                    "fewer samples");
  return command;
}

void checkMergeArguments(const MergeOptions& options) {
  prepareOutputFile(options.out, {".exr"}, "--out");
  prepareOutputFile(options.report, {".json"}, "--report");
  for (const std::string& part : options.parts) passes::readReferencePartial(part);
}

void runMerge(const MergeOptions& options, const vk::Context& context, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::filesystem::path> paths(options.parts.begin(), options.parts.end());
  vk::FrameRecorder frame(context);
  const passes::MergedReference merged = passes::mergeReferenceParts(context, frame, paths, options.allowPartial);
  io::writeExr(options.out, io::LayeredImage{merged.width, merged.height,
                                             {vec4Layer("", {"R", "G", "B", "A"}, merged.color)}});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const uint32_t shards = merged.parts.front().shardCount;
  const std::string held = std::to_string(merged.samplesHeld) + " of " + std::to_string(merged.samples) +
                           " samples per pixel";
  if (merged.samplesHeld < merged.samples && !quiet)
    std::cerr << "hmblur: warning: merged " << merged.parts.size() << " of " << shards << " shards (--allow-partial): "
              << held << '\n';
  if (!options.report.empty()) {
    nlohmann::json parts = nlohmann::json::array();
    for (size_t i = 0; i < merged.parts.size(); ++i) {
      const passes::ReferencePartial& part = merged.parts[i];
      parts.push_back({{"file", options.parts[i]},
                       {"shard", part.shardText()},
                       {"first_sample", part.shard.begin},
                       {"end_sample", part.shard.end},
                       {"samples_done", part.samplesDone},
                       {"tree_nodes", part.nodes.size()}});
    }
    const nlohmann::json report = {{"tool", "hmblur merge"},
                                   {"date", utcTimestamp()},
                                   {"device", deviceJson(context)},
                                   {"system", systemJson(querySystemInfo())},
                                   {"version", merged.parts.front().version},
                                   {"render", merged.parts.front().identity},
                                   {"samples", merged.samples},
                                   {"samples_merged", merged.samplesHeld},
                                   {"shards", shards},
                                   {"missing_shards", merged.missingShards},
                                   {"parts", parts},
                                   {"image", options.out},
                                   {"device_ms", optionalNumber(merged.timings.frameMilliseconds)},
                                   {"wall_s", seconds}};
    writeJson(options.report, report);
  }
  if (!quiet)
    std::cout << "merge: " << merged.parts.size() << " of " << shards << " shards, " << held << " -> " << options.out
              << '\n';
}

}  // namespace hmb::cli
