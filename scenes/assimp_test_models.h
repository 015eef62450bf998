// Debian's assimp-testmodels: real glTF files the tests and benchmarks use when the package is
// installed (scripts/install-deps.sh installs it).
#pragma once

#include <filesystem>

namespace hmb::scene {

// The folder of the package's glTF 2.0 models, or an empty path when it is not installed.
std::filesystem::path assimpGltfModels();

}  // namespace hmb::scene
