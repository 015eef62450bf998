// The committed malformed-glTF corpus (tests/scenes/malformed/, written by its generate.py), for
// the loader's and the CLI's tests; HMB_MALFORMED_CORPUS_DIR is set by their CMakeLists.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace hmb::test {

// Far fewer files than this means the corpus is missing, not that every file passed.
inline constexpr size_t kMalformedCorpusMinFiles = 30;

inline std::vector<std::filesystem::path> malformedCorpusFiles() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(HMB_MALFORMED_CORPUS_DIR)) {
    const std::string ext = entry.path().extension().string();
    if (ext == ".gltf" || ext == ".glb") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace hmb::test
