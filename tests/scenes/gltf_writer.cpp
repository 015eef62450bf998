#include "tests/scenes/gltf_writer.h"

#include <cstring>
#include <fstream>

namespace hmb::scene::test {
namespace {

void putBigEndian32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

uint32_t crc32(const uint8_t* data, size_t size) {
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void putChunk(std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& payload) {
  putBigEndian32(png, static_cast<uint32_t>(payload.size()));
  std::vector<uint8_t> typed(type, type + 4);
  typed.insert(typed.end(), payload.begin(), payload.end());
  png.insert(png.end(), typed.begin(), typed.end());
  putBigEndian32(png, crc32(typed.data(), typed.size()));
}

void putLittleEndian32(std::vector<uint8_t>& out, uint32_t v) {
  for (int shift = 0; shift < 32; shift += 8) out.push_back(static_cast<uint8_t>(v >> shift));
}

}  // namespace

std::string base64(const uint8_t* data, size_t size) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < size; i += 3) {
    const uint32_t chunk = (uint32_t{data[i]} << 16) | (i + 1 < size ? uint32_t{data[i + 1]} << 8 : 0) |
                           (i + 2 < size ? uint32_t{data[i + 2]} : 0);
    out += alphabet[(chunk >> 18) & 63];
    out += alphabet[(chunk >> 12) & 63];
    out += i + 1 < size ? alphabet[(chunk >> 6) & 63] : '=';
    out += i + 2 < size ? alphabet[chunk & 63] : '=';
  }
  return out;
}

std::vector<uint8_t> encodePng(uint32_t width, uint32_t height, int channels, int bitDepth,
                               const std::vector<uint16_t>& samples) {
  std::vector<uint8_t> raw;
  const size_t rowSamples = size_t{width} * static_cast<size_t>(channels);
  for (uint32_t y = 0; y < height; ++y) {
    raw.push_back(0);  // filter: none
    for (size_t s = 0; s < rowSamples; ++s) {
      const uint16_t v = samples[y * rowSamples + s];
      if (bitDepth == 16) raw.push_back(static_cast<uint8_t>(v >> 8));
      raw.push_back(static_cast<uint8_t>(v));
    }
  }
  // zlib stream of stored blocks.
  std::vector<uint8_t> z = {0x78, 0x01};
  size_t pos = 0;
  do {
    const size_t n = std::min<size_t>(65535, raw.size() - pos);
    z.push_back(pos + n == raw.size() ? 1 : 0);
    z.push_back(static_cast<uint8_t>(n));
    z.push_back(static_cast<uint8_t>(n >> 8));
    z.push_back(static_cast<uint8_t>(~n));
    z.push_back(static_cast<uint8_t>(~n >> 8));
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(pos),
             raw.begin() + static_cast<std::ptrdiff_t>(pos + n));
    pos += n;
  } while (pos < raw.size());
  uint32_t a = 1, b = 0;
  for (uint8_t byte : raw) {
    a = (a + byte) % 65521;
    b = (b + a) % 65521;
  }
  putBigEndian32(z, (b << 16) | a);

  static const int colorTypes[] = {0, 0, 4, 2, 6};
  std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<uint8_t> header;
  putBigEndian32(header, width);
  putBigEndian32(header, height);
  header.insert(header.end(), {static_cast<uint8_t>(bitDepth), static_cast<uint8_t>(colorTypes[channels]), 0, 0, 0});
  putChunk(png, "IHDR", header);
  putChunk(png, "IDAT", z);
  putChunk(png, "IEND", {});
  return png;
}

std::filesystem::path testDataDir(const std::string& testName) {
  const std::filesystem::path dir = std::filesystem::path(HMB_TEST_DATA_DIR) / "scenes" / testName;
  std::filesystem::create_directories(dir);
  return dir;
}

GltfWriter::GltfWriter() {
  doc["asset"] = {{"version", "2.0"}};
  doc["scene"] = 0;
  doc["scenes"] = nlohmann::json::array({nlohmann::json{{"nodes", nlohmann::json::array()}}});
}

int GltfWriter::addView(const void* data, size_t bytes, size_t byteStride) {
  while (bin.size() % 4 != 0) bin.push_back(0);
  nlohmann::json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
  if (byteStride != 0) view["byteStride"] = byteStride;
  const auto* p = static_cast<const uint8_t*>(data);
  bin.insert(bin.end(), p, p + bytes);
  doc["bufferViews"].push_back(view);
  return static_cast<int>(doc["bufferViews"].size() - 1);
}

int GltfWriter::addAccessor(int view, int componentType, size_t count, const std::string& type, size_t byteOffset,
                            bool normalized) {
  nlohmann::json acc = {{"componentType", componentType}, {"count", count}, {"type", type}};
  if (view >= 0) acc["bufferView"] = view;
  if (byteOffset != 0) acc["byteOffset"] = byteOffset;
  if (normalized) acc["normalized"] = true;
  doc["accessors"].push_back(acc);
  return static_cast<int>(doc["accessors"].size() - 1);
}

int GltfWriter::addFloats(const std::vector<float>& values, const std::string& type) {
  const size_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : 4;
  const int view = addView(values.data(), values.size() * sizeof(float));
  return addAccessor(view, kFloat, values.size() / components, type);
}

int GltfWriter::addIndices(const std::vector<uint32_t>& indices, int componentType) {
  std::vector<uint8_t> bytes;
  for (uint32_t i : indices) {
    if (componentType == kUnsignedByte) bytes.push_back(static_cast<uint8_t>(i));
    if (componentType == kUnsignedShort) {
      bytes.push_back(static_cast<uint8_t>(i));
      bytes.push_back(static_cast<uint8_t>(i >> 8));
    }
    if (componentType == kUnsignedInt) putLittleEndian32(bytes, i);
  }
  const int view = addView(bytes.data(), bytes.size());
  return addAccessor(view, componentType, indices.size(), "SCALAR");
}

int GltfWriter::addNode(nlohmann::json node) {
  doc["nodes"].push_back(std::move(node));
  return static_cast<int>(doc["nodes"].size() - 1);
}

int GltfWriter::addMesh(const std::vector<nlohmann::json>& primitives) {
  doc["meshes"].push_back({{"primitives", primitives}});
  return static_cast<int>(doc["meshes"].size() - 1);
}

void GltfWriter::setSceneRoots(const std::vector<int>& roots) { doc["scenes"][0]["nodes"] = roots; }

std::filesystem::path GltfWriter::writeGltf(const std::filesystem::path& path, bool externalBin) const {
  nlohmann::json out = doc;
  if (!bin.empty()) {
    if (externalBin) {
      const std::filesystem::path binPath = path.parent_path() / (path.stem().string() + ".bin");
      std::ofstream(binPath, std::ios::binary)
          .write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
      out["buffers"] = {{{"byteLength", bin.size()}, {"uri", binPath.filename().string()}}};
    } else {
      out["buffers"] = {{{"byteLength", bin.size()},
                         {"uri", "data:application/octet-stream;base64," + base64(bin.data(), bin.size())}}};
    }
  }
  std::ofstream(path) << out.dump(1);
  return path;
}

std::vector<uint8_t> GltfWriter::glbBytes() const {
  nlohmann::json out = doc;
  std::vector<uint8_t> payload = bin;
  while (payload.size() % 4 != 0) payload.push_back(0);
  if (!bin.empty()) out["buffers"] = {{{"byteLength", bin.size()}}};
  std::string json = out.dump();
  while (json.size() % 4 != 0) json += ' ';
  std::vector<uint8_t> glb;
  const uint32_t total =
      12 + 8 + static_cast<uint32_t>(json.size()) + (payload.empty() ? 0 : 8 + static_cast<uint32_t>(payload.size()));
  glb.insert(glb.end(), {'g', 'l', 'T', 'F'});
  putLittleEndian32(glb, 2);
  putLittleEndian32(glb, total);
  putLittleEndian32(glb, static_cast<uint32_t>(json.size()));
  glb.insert(glb.end(), {'J', 'S', 'O', 'N'});
  glb.insert(glb.end(), json.begin(), json.end());
  if (!payload.empty()) {
    putLittleEndian32(glb, static_cast<uint32_t>(payload.size()));
    glb.insert(glb.end(), {'B', 'I', 'N', 0});
    glb.insert(glb.end(), payload.begin(), payload.end());
  }
  return glb;
}

std::filesystem::path GltfWriter::writeGlb(const std::filesystem::path& path) const {
  const std::vector<uint8_t> glb = glbBytes();
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(glb.data()), static_cast<std::streamsize>(glb.size()));
  return path;
}

nlohmann::json addQuadPrimitive(GltfWriter& w, float size, bool withUv) {
  const int positions = w.addFloats({0, 0, 0, size, 0, 0, size, size, 0, 0, size, 0}, "VEC3");
  const int indices = w.addIndices({0, 1, 2, 0, 2, 3}, kUnsignedShort);
  nlohmann::json prim = {{"attributes", {{"POSITION", positions}}}, {"indices", indices}};
  if (withUv) prim["attributes"]["TEXCOORD_0"] = w.addFloats({0, 0, 1, 0, 1, 1, 0, 1}, "VEC2");
  return prim;
}

}  // namespace hmb::scene::test
