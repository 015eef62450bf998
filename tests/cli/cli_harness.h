// Running the hmblur executable (HMB_CLI_PATH) and the example programs as a user does: their
// output, exit code and the shape of their errors. Every hmblur command runs with
// --validation, so a validation error fails it with exit code 3.
#pragma once

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

namespace hmb::test {

struct CliRun {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

// Runs `program args` through the shell, stdout and stderr together.
inline CliRun runProgram(const std::string& program, const std::string& args) {
  const std::string command = program + " " + args + " 2>&1";
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> chunk{};
  while (size_t n = fread(chunk.data(), 1, chunk.size(), pipe)) run.output.append(chunk.data(), n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

inline CliRun hmblur(const std::string& args) { return runProgram(HMB_CLI_PATH, "--validation " + args); }

// An empty folder of the test's own under the test temp dir.
inline std::filesystem::path tempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(testing::TempDir()) / ("hmblur_cli_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A user error is one line on stderr naming the problem, and a non-zero exit (commands
// checked with this run --quiet, so progress lines do not count).
inline void expectOneLineError(const CliRun& run, const std::string& needle) {
  EXPECT_NE(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find(needle), std::string::npos) << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
}

}  // namespace hmb::test
