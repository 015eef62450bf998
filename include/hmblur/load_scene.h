// One entry point for "which scene": a glTF path or a reference scene name.
#pragma once

#include <optional>
#include <string_view>

#include "hmblur/scene.h"

namespace hmb::scene {

// A glTF file says nothing of a shutter: it is played as film and games are, at kGltfFps with a
// shutter of kGltfShutterAngleDegrees (the reference scenes keep the paper's settings).
inline constexpr float kGltfFps = 24.0f;
inline constexpr float kGltfShutterAngleDegrees = 180.0f;

// The shutter a render asks for where the scene's own is not wanted. The exposure is given in
// seconds or as a shutter angle (360 degrees: the whole frame interval), not both; an angle
// alone applies at the scene's frame rate (or the one chosen with it).
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
