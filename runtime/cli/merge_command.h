// hmblur merge: the parts of a reference render split into shards (render --shard I/K) joined
// into the image of the whole render, bit for bit (runtime/passes/reference_merge.h).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace hmb::vk {
class Context;
}

namespace hmb::cli {

struct MergeOptions {
  std::vector<std::string> parts;
  std::string out;     // .exr
  std::string report;  // .json; empty: none
  bool allowPartial = false;
};

// Registers the subcommand on `app`; `options` must outlive the parse.
CLI::App* addMergeCommand(CLI::App& app, MergeOptions& options);

// What can be checked before a device is opened: the outputs can be written and every part is
// a reference partial. Throws hmb::Error.
void checkMergeArguments(const MergeOptions& options);

// Merges, writes the image and the report, and says what it merged on stdout and, for a merge
// of fewer samples than the render's, on stderr (nothing with `quiet`). Throws hmb::Error.
void runMerge(const MergeOptions& options, const vk::Context& context, bool quiet);

}  // namespace hmb::cli
