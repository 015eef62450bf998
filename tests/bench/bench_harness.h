// What the hmblur-bench tests share: the program run as a user runs it, with --validation (a
// validation error fails it with exit code 3) and --quiet, and its JSON reports read back.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli/cli_harness.h"

namespace hmb::test {

inline CliRun bench(const std::string& args) { return runProgram(HMB_BENCH_PATH, "--validation --quiet " + args); }

inline nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace hmb::test
