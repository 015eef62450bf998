// The reference scenes and the motion studies by name.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "hmblur/scene.h"

namespace hmb::scene {

// "living-room", "temple", "bistro".
std::vector<std::string> referenceSceneNames();

// "spinning-plate", "turntable", "spinning-box": motion studies, made to isolate one kind of
// screen motion (scenes/procedural/procedural_scenes.h); not reference scenes.
std::vector<std::string> motionStudyNames();

// Builds a reference scene or a motion study (deterministic: the same scene on every call and
// platform). Throws hmb::Error listing the valid names when `name` is not one of them.
Scene makeReferenceScene(std::string_view name);

}  // namespace hmb::scene
