// glTF 2.0 (.gltf / .glb) into the scene model.
#pragma once

#include <filesystem>

#include "hmblur/scene.h"

namespace hmb::scene {

// Loads the default scene of a glTF file (or scene 0, or every root node when the file has
// no scenes). Triangle primitives become meshes; lines and points are skipped and counted in
// Scene::stats. Everything read from the file is validated: a malformed file throws
// hmb::Error with a one-line message that starts with the path. Does not call
// deriveDefaults. When the file is animated, settings.frameTime is set to the middle of the
// animation's time range so that the default frame shows motion.
Scene loadGltf(const std::filesystem::path& path);

}  // namespace hmb::scene
