// libFuzzer target of the scene loader: any bytes, saved as a .glb (when they start with the
// binary magic) or a .gltf file, must load into a scene or fail with hmb::Error. Anything
// else (a crash, another exception, a sanitizer report, a hang) is a finding. Run by
// fuzz/run.sh; README.md there.
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "hmblur/error.h"
#include "hmblur/load_scene.h"

namespace {

// One folder per fuzzing process, so parallel jobs do not share input files.
const std::filesystem::path& inputDir() {
  static const std::filesystem::path dir = [] {
    const auto path = std::filesystem::temp_directory_path() / ("hmb-gltf-fuzz-" + std::to_string(getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  const std::filesystem::path path = inputDir() / (binary ? "input.glb" : "input.gltf");
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    (void)hmb::scene::loadScene(path.string());
  } catch (const hmb::Error&) {
    // A clear error is the right answer to a malformed file.
  }
  return 0;
}
