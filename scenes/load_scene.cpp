#include "scenes/load_scene.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "scenes/gltf_loader.h"
#include "scenes/reference_scenes.h"

namespace hmb::scene {
namespace {

bool endsWithNoCase(std::string_view text, std::string_view suffix) {
  if (text.size() < suffix.size()) return false;
  return std::equal(suffix.begin(), suffix.end(), text.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                    [](char a, char b) {
                      return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
                    });
}

}  // namespace

Scene loadScene(std::string_view nameOrPath) {
  Scene scene = endsWithNoCase(nameOrPath, ".gltf") || endsWithNoCase(nameOrPath, ".glb")
                    ? loadGltf(std::filesystem::path(std::string(nameOrPath)))
                    : makeReferenceScene(nameOrPath);
  deriveDefaults(scene);
  return scene;
}

}  // namespace hmb::scene
