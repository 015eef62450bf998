// Scratch files for the io tests, one per test so tests may run in parallel.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "hmblur/error.h"
#include "tests/support/expect_error.h"

namespace hmb::io::testing {

// A fresh path in the test data folder, named after the running test plus a suffix.
inline std::filesystem::path scratchPath(const std::string& suffix) {
  const std::filesystem::path dir = std::filesystem::path(HMB_TEST_DATA_DIR) / "io";
  std::filesystem::create_directories(dir);
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::filesystem::path path =
      dir / (std::string(info->test_suite_name()) + "_" + info->name() + suffix);
  std::filesystem::remove(path);
  return path;
}

// "_7x3.exr": keeps the files of a size sweep apart.
inline std::string sizeSuffix(uint32_t width, uint32_t height, const std::string& extension) {
  std::string suffix = "_";
  suffix += std::to_string(width);
  suffix += 'x';
  suffix += std::to_string(height);
  suffix += extension;
  return suffix;
}

inline void writeBytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

inline std::string randomBytes(size_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::string bytes(count, '\0');
  for (char& b : bytes) b = char(rng() & 0xff);
  return bytes;
}

inline std::string readBytes(const std::filesystem::path& path) {
  std::ifstream stream(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

using hmb::test::expectError;

}  // namespace hmb::io::testing
