// One entry point for "which scene": a glTF path or a reference scene name.
#pragma once

#include <string_view>

#include "scenes/scene.h"

namespace hmb::scene {

// A path ending in .gltf or .glb (any case) is loaded from disk; anything else names a
// reference scene. Either way deriveDefaults has been applied. Throws hmb::Error (missing
// file: "<path>: no such file"; unknown name: the list of valid names).
Scene loadScene(std::string_view nameOrPath);

}  // namespace hmb::scene
