// One entry point for "which scene": a glTF path or a reference scene name.
#pragma once

#include <optional>
#include <string_view>

#include "hmblur/scene.h"

namespace hmb::scene {

// The shutter a render asks for where the scene's own is not wanted (a glTF file has none:
// Settings' defaults apply). The exposure is given in seconds or as a shutter angle (360
// degrees: the whole frame interval), not both.
struct ShutterChoice {
  std::optional<float> fps;
  std::optional<float> exposureSeconds;
  std::optional<float> shutterAngleDegrees;
};

// A path ending in .gltf or .glb (any case), or an existing file that holds glTF, is loaded
// from disk; anything else names a reference scene. Either way the shutter choice is applied
// and then deriveDefaults (near and far planes hold what the shutter sees). Throws
// hmb::Error (missing file: "<path>: no such file"; unknown name: the list of valid names; a
// directory or an image: what it is; an absurd shutter).
Scene loadScene(std::string_view nameOrPath, const ShutterChoice& shutter = {});

// Settings' fps and exposure after the choice; throws hmb::Error naming an absurd value.
void applyShutterChoice(const ShutterChoice& shutter, Settings& settings);

}  // namespace hmb::scene
