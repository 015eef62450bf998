// Scenes the benchmarks add to the reference scenes and glTF files: sizes that no reference
// scene reaches, made in code so that nothing large is committed.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "hmblur/scene.h"

namespace hmb::bench {

// One static unit sphere of 1,009,200 triangles (a cube's faces tessellated 290 x 290 and
// pushed out), flat +z normals: the bvh suite's large mesh.
inline constexpr const char* kCubeSphere1m = "cube-sphere-1m";
// A sphere of 1,000,000 triangles behind a box sliding across it, lit and shaded: the
// passes suite's check of the hybrid frame on a scene of a million triangles.
inline constexpr const char* kMillionTriangles = "million-triangles";

// A real CAD asset: 2CylinderEngine from Debian's assimp-testmodels (110k triangles in
// millimetres, many of them long and thin, with thousands of degenerate ones). Its path, or
// nothing when the package is not installed.
inline constexpr const char* kCadEngine = "cad-engine";
std::optional<std::filesystem::path> cadEnginePath();

// These names, else scene::loadScene (a reference scene or a glTF file).
scene::Scene loadBenchScene(const std::string& name);

// A scene's name in file names: a glTF file's stem, else the name itself.
std::string sceneStem(const std::string& scene);

}  // namespace hmb::bench
