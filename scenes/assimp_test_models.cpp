#include "scenes/assimp_test_models.h"

namespace hmb::scene {

std::filesystem::path assimpGltfModels() {
  // Debian 12 installs them under the first; other releases have used the second.
  for (const char* root : {"/usr/share/assimp/models/glTF2", "/usr/share/assimp-testmodels/glTF2"})
    if (std::filesystem::is_directory(root)) return root;
  return {};
}

}  // namespace hmb::scene
