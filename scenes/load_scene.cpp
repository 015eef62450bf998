#include "hmblur/load_scene.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hmblur/error.h"
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

// What a file that is not named .gltf or .glb holds, by its first bytes: a glTF (binary, or JSON
// that may be one) is loaded; anything else is refused, saying what it is.
bool loadableAsGltf(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw Error(path.string() + ": a directory, not a glTF file (.gltf or .glb)");
  std::ifstream in(path, std::ios::binary);
  unsigned char head[8] = {};
  in.read(reinterpret_cast<char*>(head), sizeof(head));
  const auto starts = [&](std::string_view magic) {
    return static_cast<size_t>(in.gcount()) >= magic.size() && std::memcmp(head, magic.data(), magic.size()) == 0;
  };
  if (starts("glTF") || starts("{")) return true;
  const char* kind = starts("\x89PNG") ? "a PNG image" : starts("\xff\xd8\xff") ? "a JPEG image" : "not a glTF file";
  throw Error(path.string() + ": " + kind + ", not a scene (a .gltf or .glb file, or a reference scene name)");
}

}  // namespace

void applyShutterChoice(const ShutterChoice& shutter, Settings& settings) {
  constexpr float kMaxFps = 10000.0f, kMaxExposure = 1.0f, kMaxAngle = 3600.0f;
  const auto text = [](float v) {
    std::ostringstream out;
    out << v;
    return out.str();
  };
  if (shutter.exposureSeconds && shutter.shutterAngleDegrees)
    throw Error("give the exposure in seconds or as a shutter angle, not both");
  if (shutter.fps) {
    if (!(*shutter.fps >= 1.0f && *shutter.fps <= kMaxFps))
      throw Error("fps " + text(*shutter.fps) + " must be 1 to " + text(kMaxFps) + " frames per second");
    settings.fps = *shutter.fps;
  }
  if (shutter.exposureSeconds) {
    if (!(*shutter.exposureSeconds >= 0.0f && *shutter.exposureSeconds <= kMaxExposure))
      throw Error("exposure " + text(*shutter.exposureSeconds) + " must be 0 to " + text(kMaxExposure) + " s");
    settings.exposure = *shutter.exposureSeconds;
  }
  if (shutter.shutterAngleDegrees) {
    if (!(*shutter.shutterAngleDegrees >= 0.0f && *shutter.shutterAngleDegrees <= kMaxAngle))
      throw Error("shutter angle " + text(*shutter.shutterAngleDegrees) + " must be 0 to " + text(kMaxAngle) +
                  " degrees");
    settings.exposure = *shutter.shutterAngleDegrees / 360.0f / settings.fps;
  }
}

Scene loadScene(std::string_view nameOrPath, const ShutterChoice& shutter) {
  const std::filesystem::path path{std::string(nameOrPath)};
  std::error_code ec;
  std::vector<std::string> names = referenceSceneNames();
  for (std::string& study : motionStudyNames()) names.push_back(std::move(study));
  const bool named = std::find(names.begin(), names.end(), nameOrPath) != names.end();
  const bool gltf = endsWithNoCase(nameOrPath, ".gltf") || endsWithNoCase(nameOrPath, ".glb") ||
                    (!named && std::filesystem::exists(path, ec) && loadableAsGltf(path));
  Scene scene = gltf ? loadGltf(path) : makeReferenceScene(nameOrPath);
  if (gltf) {
    scene.settings.fps = kGltfFps;
    scene.settings.exposure = kGltfShutterAngleDegrees / 360.0f / kGltfFps;
  }
  applyShutterChoice(shutter, scene.settings);
  deriveDefaults(scene);
  return scene;
}

}  // namespace hmb::scene
