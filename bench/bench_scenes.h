// Scenes the benchmarks add to the reference scenes and glTF files: sizes that no reference
// scene reaches, made in code so that nothing large is committed.
#pragma once

#include <string>

#include "scenes/scene.h"

namespace hmb::bench {

// One static unit sphere of 1,009,200 triangles (a cube's faces tessellated 290 x 290 and
// pushed out), flat +z normals: the bvh suite's large mesh.
inline constexpr const char* kCubeSphere1m = "cube-sphere-1m";
// A sphere of 1,000,000 triangles behind a box sliding across it, lit and shaded: the
// passes suite's check of the hybrid frame on a scene of a million triangles.
inline constexpr const char* kMillionTriangles = "million-triangles";

// These names, else scene::loadScene (a reference scene or a glTF file).
scene::Scene loadBenchScene(const std::string& name);

}  // namespace hmb::bench
