// The reference scenes by name.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "scenes/scene.h"

namespace hmb::scene {

// "living-room", "temple", "bistro".
std::vector<std::string> referenceSceneNames();

// Builds a reference scene (deterministic: the same scene on every call and platform).
// Throws hmb::Error listing the valid names when `name` is not one of them.
Scene makeReferenceScene(std::string_view name);

}  // namespace hmb::scene
