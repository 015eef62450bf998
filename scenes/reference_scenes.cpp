#include "scenes/reference_scenes.h"

#include <span>

#include "hmblur/error.h"
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

constexpr Entry kMotionStudies[] = {
    {"spinning-plate", &procedural::makeSpinningPlate},
    {"turntable", &procedural::makeTurntable},
    {"spinning-box", &procedural::makeSpinningBox},
};

}  // namespace

std::vector<std::string> referenceSceneNames() {
  std::vector<std::string> names;
  for (const Entry& e : kScenes) names.emplace_back(e.name);
  return names;
}

std::vector<std::string> motionStudyNames() {
  std::vector<std::string> names;
  for (const Entry& e : kMotionStudies) names.emplace_back(e.name);
  return names;
}

Scene makeReferenceScene(std::string_view name) {
  for (const auto& table : {std::span<const Entry>(kScenes), std::span<const Entry>(kMotionStudies)})
    for (const Entry& e : table)
      if (name == e.name) return e.make();
  const auto list = [](std::span<const Entry> table) {
    std::string names;
    for (const Entry& e : table) names += std::string(names.empty() ? "" : ", ") + e.name;
    return names;
  };
  throw Error("unknown scene '" + std::string(name) + "' (reference scenes: " + list(kScenes) +
              "; motion studies: " + list(kMotionStudies) + "; or a path to a .gltf/.glb file)");
}

}  // namespace hmb::scene
