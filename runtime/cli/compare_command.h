// hmblur compare: error metrics of rendered images against a reference (runtime/metrics/).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace hmb::cli {

struct CompareOptions {
  std::string reference;
  std::vector<std::string> images;
  std::string sharp;           // the sharp frame that defines the blur region; empty: no region
  std::string json;            // JSON file to write; empty: none
  std::string errorImagesDir;  // folder for one FLIP error PNG per image; empty: none
  float pixelsPerDegree = 67.0f;
};

// Registers the subcommand on `app`; `options` must outlive the parse.
CLI::App* addCompareCommand(CLI::App& app, CompareOptions& options);

// Prints the table on stdout and writes the files asked for; throws hmb::Error on user errors.
int runCompare(const CompareOptions& options);

}  // namespace hmb::cli
