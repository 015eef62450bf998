#include "scenes/reference_scenes.h"

#include "runtime/error.h"
#include "scenes/procedural/procedural_scenes.h"

namespace hmb::scene {
namespace {

struct Entry {
  const char* name;
  Scene (*make)();
};

constexpr Entry kScenes[] = {
    {"living-room", &procedural::makeLivingRoom},
    {"temple", &procedural::makeTemple},
    {"bistro", &procedural::makeBistro},
};

}  // namespace

std::vector<std::string> referenceSceneNames() {
  std::vector<std::string> names;
  for (const Entry& e : kScenes) names.emplace_back(e.name);
  return names;
}

Scene makeReferenceScene(std::string_view name) {
  for (const Entry& e : kScenes)
    if (name == e.name) return e.make();
  std::string valid;
  for (const Entry& e : kScenes) valid += std::string(valid.empty() ? "" : ", ") + e.name;
  throw Error("unknown scene '" + std::string(name) + "' (reference scenes: " + valid +
              "; or a path to a .gltf/.glb file)");
}

}  // namespace hmb::scene
