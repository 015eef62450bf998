// Writes small glTF files for the loader tests: JSON with an embedded (data URI) buffer, or
// GLB, plus a minimal PNG encoder for textures.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hmb::scene::test {

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;

std::string base64(const uint8_t* data, size_t size);

// PNG with stored (uncompressed) deflate blocks. channels 1-4, bitDepth 8 or 16; samples
// row by row, one value per channel (16-bit values as they are, 8-bit in 0..255).
std::vector<uint8_t> encodePng(uint32_t width, uint32_t height, int channels, int bitDepth,
                               const std::vector<uint16_t>& samples);

// Per-test scratch directory inside the build tree.
std::filesystem::path testDataDir(const std::string& testName);

class GltfWriter {
 public:
  GltfWriter();

  nlohmann::json doc;
  std::vector<uint8_t> bin;

  // Appends raw bytes (4-byte aligned) and a buffer view over them; returns the view index.
  int addView(const void* data, size_t bytes, size_t byteStride = 0);
  int addAccessor(int view, int componentType, size_t count, const std::string& type, size_t byteOffset = 0,
                  bool normalized = false);
  int addFloats(const std::vector<float>& values, const std::string& type);
  int addIndices(const std::vector<uint32_t>& indices, int componentType = kUnsignedInt);
  int addNode(nlohmann::json node);
  // A mesh with one primitive per entry of `primitives`.
  int addMesh(const std::vector<nlohmann::json>& primitives);
  void setSceneRoots(const std::vector<int>& roots);

  // Writes .gltf with the buffer as a data URI (or a file next to it when externalBin).
  std::filesystem::path writeGltf(const std::filesystem::path& path, bool externalBin = false) const;
  std::filesystem::path writeGlb(const std::filesystem::path& path) const;
  std::vector<uint8_t> glbBytes() const;
};

// A unit quad in z = 0 (two triangles, 4 vertices, indexed) as a primitive JSON.
nlohmann::json addQuadPrimitive(GltfWriter& w, float size = 1.0f, bool withUv = false);

}  // namespace hmb::scene::test
