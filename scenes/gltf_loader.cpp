#include "scenes/gltf_loader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "hmblur/error.h"

namespace hmb::scene {
namespace {

namespace fs = std::filesystem;

// Far beyond any real asset, small enough that a hostile count cannot exhaust memory.
constexpr uint64_t kMaxElements = uint64_t{1} << 27;
constexpr size_t kMaxNodes = size_t{1} << 24;

std::string toLower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// tinygltf reports several lines; our errors are one line.
std::string oneLine(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n' || c == '\r') {
      if (!out.empty() && out.back() != ' ') out += "; ";
    } else {
      out += c;
    }
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
  return out;
}

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;  // a skin's inverse bind matrices
    default: return 0;  // other matrices are never data we read
  }
}

int componentSize(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

template <typename T>
T readUnaligned(const uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// One component, as the glTF spec maps normalized integers to [0, 1] or [-1, 1].
double decodeComponent(const uint8_t* p, int componentType, bool normalized) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const double v = readUnaligned<int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      const double v = readUnaligned<uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      const double v = readUnaligned<int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      const double v = readUnaligned<uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      const double v = readUnaligned<uint32_t>(p);
      return normalized ? v / 4294967295.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return readUnaligned<float>(p);
    default: return 0.0;
  }
}

std::optional<AnimationPath> animationPath(const std::string& path) {
  if (path == "translation") return AnimationPath::Translation;
  if (path == "rotation") return AnimationPath::Rotation;
  if (path == "scale") return AnimationPath::Scale;
  if (path == "weights") return AnimationPath::Weights;
  return std::nullopt;  // extension paths: not part of the scene model
}

std::optional<Interpolation> interpolationOf(const std::string& name) {
  if (name.empty() || name == "LINEAR") return Interpolation::Linear;
  if (name == "STEP") return Interpolation::Step;
  if (name == "CUBICSPLINE") return Interpolation::CubicSpline;
  return std::nullopt;
}

// Finite as the floats the scene holds: 1e300 is a finite double but Inf as a float.
bool finiteAsFloat(double v) { return std::isfinite(static_cast<float>(v)); }

bool allFinite(const std::vector<double>& values) { return std::all_of(values.begin(), values.end(), finiteAsFloat); }

// The extensions this loader implements (glTF 2.0 spec, 3.12): a file that requires any other
// is refused; one that only uses another loads without it, with a warning. Quantized
// geometry needs nothing more than readAccessor, which decodes every component type;
// punctual lights are read where directional (others are ignored with a warning).
bool implementedExtension(const std::string& name) {
  return name == "KHR_mesh_quantization" || name == "KHR_lights_punctual";
}

struct Bytes {
  const uint8_t* data = nullptr;
  size_t size = 0;
};

class GltfImporter {
 public:
  GltfImporter(const fs::path& path, const tinygltf::Model& model) : path_(path), model_(model) {}

  Scene run() {
    scene_.name = path_.stem().string();
    checkExtensions();
    warnOfIgnoredMaterialProperties();
    buildNodes();
    readSkins();
    readAnimations();
    placeContent();
    if (scene_.triangleCount() == 0) warn("no triangles to draw: the image shows the background only");
    return std::move(scene_);
  }

  [[noreturn]] void fail(const std::string& message) const { throw Error(path_.string() + ": " + message); }
  void warn(const std::string& message) { scene_.stats.warnings.push_back(message); }

 private:
  // --- raw data --------------------------------------------------------------------------

  Bytes viewBytes(int viewIndex, const std::string& user) const {
    if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model_.bufferViews.size())
      fail(user + " refers to buffer view " + std::to_string(viewIndex) + ", which does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(viewIndex)];
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model_.buffers.size())
      fail("buffer view " + std::to_string(viewIndex) + " refers to buffer " + std::to_string(view.buffer) +
           ", which does not exist");
    const tinygltf::Buffer& buffer = model_.buffers[static_cast<size_t>(view.buffer)];
    if (buffer.data.empty())
      fail("buffer " + std::to_string(view.buffer) + " has no data (missing or empty buffer file)");
    if (view.byteOffset > buffer.data.size() || view.byteLength > buffer.data.size() - view.byteOffset)
      fail("buffer view " + std::to_string(viewIndex) + " (bytes " + std::to_string(view.byteOffset) + "+" +
           std::to_string(view.byteLength) + ") lies outside buffer " + std::to_string(view.buffer) + " of " +
           std::to_string(buffer.data.size()) + " bytes");
    return Bytes{buffer.data.data() + view.byteOffset, view.byteLength};
  }

  // Reads an accessor (strided view, then its sparse substitutions) into doubles,
  // `components` per element. `what` names the use, for messages.
  std::vector<double> readAccessor(int index, const std::string& what, std::initializer_list<int> allowedTypes,
                                   int* componentsOut = nullptr) const {
    if (index < 0 || static_cast<size_t>(index) >= model_.accessors.size())
      fail(what + " refers to accessor " + std::to_string(index) + ", which does not exist");
    const tinygltf::Accessor& acc = model_.accessors[static_cast<size_t>(index)];
    const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    if (std::find(allowedTypes.begin(), allowedTypes.end(), acc.type) == allowedTypes.end())
      fail(name + " has an unexpected element type");
    const int components = componentCount(acc.type);
    const int size = componentSize(acc.componentType);
    if (size == 0) fail(name + " has an unsupported component type " + std::to_string(acc.componentType));
    if (acc.count > kMaxElements || acc.count * uint64_t(std::max(components, 1)) > 4 * kMaxElements)
      fail(name + " has an absurd element count " + std::to_string(acc.count));
    if (componentsOut) *componentsOut = components;

    const size_t elementSize = static_cast<size_t>(size) * static_cast<size_t>(components);
    std::vector<double> out(acc.count * static_cast<size_t>(components), 0.0);
    if (acc.bufferView >= 0 && acc.count > 0) {
      const Bytes view = viewBytes(acc.bufferView, name);
      const size_t declaredStride = model_.bufferViews[static_cast<size_t>(acc.bufferView)].byteStride;
      const size_t stride = declaredStride != 0 ? declaredStride : elementSize;
      if (stride < elementSize) fail(name + " has a byte stride smaller than its element");
      // offset + stride * (count - 1) + elementSize <= view.size, without overflow.
      if (acc.byteOffset > view.size || elementSize > view.size - acc.byteOffset ||
          (acc.count - 1) > (view.size - acc.byteOffset - elementSize) / stride)
        fail(name + " reads past the end of buffer view " + std::to_string(acc.bufferView));
      for (size_t e = 0; e < acc.count; ++e) {
        const uint8_t* element = view.data + acc.byteOffset + e * stride;
        for (int c = 0; c < components; ++c)
          out[e * components + c] = decodeComponent(element + c * size, acc.componentType, acc.normalized);
      }
    }
    if (acc.sparse.isSparse) applySparse(acc, name, components, size, out);
    return out;
  }

  void applySparse(const tinygltf::Accessor& acc, const std::string& name, int components, int size,
                   std::vector<double>& out) const {
    const int count = acc.sparse.count;
    if (count < 0 || static_cast<size_t>(count) > acc.count) fail(name + " has an invalid sparse count");
    const int indexType = acc.sparse.indices.componentType;
    const int indexSize = componentSize(indexType);
    if (indexSize == 0 || indexType == TINYGLTF_COMPONENT_TYPE_FLOAT || indexType == TINYGLTF_COMPONENT_TYPE_BYTE ||
        indexType == TINYGLTF_COMPONENT_TYPE_SHORT)
      fail(name + " has an invalid sparse index type");
    const Bytes indices = viewBytes(acc.sparse.indices.bufferView, name + " sparse indices");
    const Bytes values = viewBytes(acc.sparse.values.bufferView, name + " sparse values");
    const size_t indexOffset = static_cast<size_t>(std::max(acc.sparse.indices.byteOffset, 0));
    const size_t valueOffset = static_cast<size_t>(std::max(acc.sparse.values.byteOffset, 0));
    const size_t elementSize = static_cast<size_t>(size * components);
    const size_t n = static_cast<size_t>(count);
    if (indexOffset > indices.size || n > (indices.size - indexOffset) / static_cast<size_t>(indexSize) ||
        valueOffset > values.size || n > (values.size - valueOffset) / elementSize)
      fail(name + " has sparse data past the end of its buffer view");
    for (size_t i = 0; i < n; ++i) {
      const double target = decodeComponent(indices.data + indexOffset + i * indexSize, indexType, false);
      if (target >= static_cast<double>(acc.count)) fail(name + " has a sparse index out of range");
      const size_t e = static_cast<size_t>(target);
      for (int c = 0; c < components; ++c)
        out[e * components + c] =
            decodeComponent(values.data + valueOffset + i * elementSize + c * size, acc.componentType, acc.normalized);
    }
  }

  std::vector<uint32_t> readIndices(int index, const std::string& what, size_t vertexCount) const {
    if (index >= 0 && static_cast<size_t>(index) < model_.accessors.size()) {
      const int type = model_.accessors[static_cast<size_t>(index)].componentType;
      if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
          type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail("accessor " + std::to_string(index) + " (" + what + ") is not of an unsigned integer type");
    }
    const std::vector<double> raw = readAccessor(index, what, {TINYGLTF_TYPE_SCALAR});
    std::vector<uint32_t> indices(raw.size());
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] >= static_cast<double>(vertexCount))
        fail("accessor " + std::to_string(index) + " (" + what + ") has index " +
             std::to_string(static_cast<uint64_t>(raw[i])) + " at element " + std::to_string(i) +
             ", past the vertex count " + std::to_string(vertexCount));
      indices[i] = static_cast<uint32_t>(raw[i]);
    }
    return indices;
  }

  // --- file level -------------------------------------------------------------------------

  // Required extensions were refused after parsing (refuseWhatCannotLoad); what is only used
  // is drawn without.
  void checkExtensions() {
    for (const std::string& ext : model_.extensionsUsed)
      if (!implementedExtension(ext)) warn("extension " + ext + " is not implemented; drawn without it");
  }

  // Material properties the shading leaves out, one warning per kind with its count.
  void warnOfIgnoredMaterialProperties() {
    size_t emissive = 0, blended = 0, masked = 0;
    for (const tinygltf::Material& m : model_.materials) {
      const bool glows = m.emissiveTexture.index >= 0 ||
                         std::any_of(m.emissiveFactor.begin(), m.emissiveFactor.end(), [](double v) { return v != 0.0; });
      emissive += glows;
      blended += m.alphaMode == "BLEND";
      masked += m.alphaMode == "MASK";
    }
    const auto count = [](size_t n) { return std::to_string(n) + (n == 1 ? " material" : " materials"); };
    if (emissive > 0) warn(count(emissive) + ": emission ignored");
    if (blended > 0) warn(count(blended) + ": alphaMode BLEND drawn opaque");
    if (masked > 0) warn(count(masked) + ": alphaMode MASK drawn opaque (no cutout)");
  }

  // --- nodes ------------------------------------------------------------------------------

  void requireFinite(const std::vector<double>& values, const std::string& what) const {
    if (!allFinite(values)) fail(what + " is not finite");
  }

  Trs decomposeMatrix(const glm::mat4& m, size_t nodeIndex) {
    Trs trs;
    trs.translation = glm::vec3(m[3]);
    const glm::mat3 linear(m);
    glm::vec3 scale(glm::length(linear[0]), glm::length(linear[1]), glm::length(linear[2]));
    // A mirroring matrix keeps working as a negative x scale.
    if (glm::determinant(linear) < 0.0f) scale.x = -scale.x;
    if (scale.x != 0.0f && scale.y != 0.0f && scale.z != 0.0f) {
      const glm::mat3 rotation(linear[0] / scale.x, linear[1] / scale.y, linear[2] / scale.z);
      trs.rotation = glm::normalize(glm::quat_cast(rotation));
    }
    trs.scale = scale;
    // TRS cannot hold shear or projection: keep the closest TRS and say so.
    const glm::mat4 back = trs.matrix();
    float error = 0.0f, magnitude = 1e-30f;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        error = std::max(error, std::abs(back[c][r] - m[c][r]));
        magnitude = std::max(magnitude, std::abs(m[c][r]));
      }
    if (error > 1e-3f * magnitude)
      warn("node " + std::to_string(nodeIndex) + " has a matrix with shear or projection; approximated by TRS");
    return trs;
  }

  Trs nodeTrs(const tinygltf::Node& node, size_t i) {
    const std::string what = "node " + std::to_string(i);
    if (!node.matrix.empty()) {
      if (node.matrix.size() != 16) fail(what + " has a matrix without 16 values");
      requireFinite(node.matrix, what + " matrix");
      glm::dmat4 m = glm::make_mat4(node.matrix.data());  // column-major, as glTF
      return decomposeMatrix(glm::mat4(m), i);
    }
    Trs trs;
    if (!node.translation.empty()) {
      if (node.translation.size() != 3) fail(what + " translation does not have 3 values");
      requireFinite(node.translation, what + " translation");
      trs.translation = glm::vec3(glm::make_vec3(node.translation.data()));
    }
    if (!node.rotation.empty()) {
      if (node.rotation.size() != 4) fail(what + " rotation does not have 4 values");
      requireFinite(node.rotation, what + " rotation");
      const glm::quat q(static_cast<float>(node.rotation[3]), static_cast<float>(node.rotation[0]),
                        static_cast<float>(node.rotation[1]), static_cast<float>(node.rotation[2]));
      const float len = glm::length(q);
      if (len > 0.0f && std::isfinite(len))
        trs.rotation = q / len;
      else
        warn(what + " has a zero rotation quaternion; identity used");
    }
    if (!node.scale.empty()) {
      if (node.scale.size() != 3) fail(what + " scale does not have 3 values");
      requireFinite(node.scale, what + " scale");
      trs.scale = glm::vec3(glm::make_vec3(node.scale.data()));
    }
    return trs;
  }

  void buildNodes() {
    const size_t count = model_.nodes.size();
    if (count > kMaxNodes) fail("has an absurd node count " + std::to_string(count));
    scene_.nodes.resize(count);
    for (size_t i = 0; i < count; ++i) {
      const tinygltf::Node& src = model_.nodes[i];
      scene_.nodes[i].name = src.name.empty() ? "node " + std::to_string(i) : src.name;
      scene_.nodes[i].local = nodeTrs(src, i);
      if (!src.weights.empty()) {
        requireFinite(src.weights, "node " + std::to_string(i) + " weights");
        scene_.nodes[i].weights.assign(src.weights.begin(), src.weights.end());
      }
    }
    for (size_t i = 0; i < count; ++i) {
      for (int child : model_.nodes[i].children) {
        if (child < 0 || static_cast<size_t>(child) >= count)
          fail("node " + std::to_string(i) + " has child " + std::to_string(child) + ", which does not exist");
        if (static_cast<size_t>(child) == i) fail("node " + std::to_string(i) + " is its own child (cycle)");
        Node& c = scene_.nodes[static_cast<size_t>(child)];
        if (c.parent >= 0)
          fail("node " + std::to_string(child) + " has two parents (" + std::to_string(c.parent) + " and " +
               std::to_string(i) + ")");
        c.parent = static_cast<int32_t>(i);
      }
    }
    // With one parent per node, a cycle is a parent chain that never reaches a root.
    // 0: unvisited, 1: on the chain being walked, 2: known to reach a root.
    std::vector<uint8_t> state(count, 0);
    std::vector<size_t> chain;
    for (size_t start = 0; start < count; ++start) {
      chain.clear();
      int64_t current = static_cast<int64_t>(start);
      while (current >= 0 && state[static_cast<size_t>(current)] == 0) {
        state[static_cast<size_t>(current)] = 1;
        chain.push_back(static_cast<size_t>(current));
        current = scene_.nodes[static_cast<size_t>(current)].parent;
      }
      if (current >= 0 && state[static_cast<size_t>(current)] == 1)
        fail("the node hierarchy has a cycle through node " + std::to_string(current));
      for (size_t n : chain) state[n] = 2;
    }
  }

  // Nodes of the rendered scene, parents before children, in file order within a level.
  std::vector<uint32_t> sceneNodesInOrder() {
    std::vector<int> roots;
    if (model_.defaultScene >= 0 && static_cast<size_t>(model_.defaultScene) < model_.scenes.size()) {
      roots = model_.scenes[static_cast<size_t>(model_.defaultScene)].nodes;
    } else if (!model_.scenes.empty()) {
      if (model_.defaultScene >= 0) warn("default scene does not exist; scene 0 used");
      roots = model_.scenes[0].nodes;
    } else {
      for (size_t i = 0; i < scene_.nodes.size(); ++i)
        if (scene_.nodes[i].parent < 0) roots.push_back(static_cast<int>(i));
    }
    std::vector<uint32_t> order;
    std::vector<uint8_t> seen(scene_.nodes.size(), 0);
    std::vector<uint32_t> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
      if (*it < 0 || static_cast<size_t>(*it) >= scene_.nodes.size())
        fail("the scene refers to node " + std::to_string(*it) + ", which does not exist");
      stack.push_back(static_cast<uint32_t>(*it));
    }
    while (!stack.empty()) {
      const uint32_t n = stack.back();
      stack.pop_back();
      if (seen[n]) continue;  // a root listed twice, or listed as root and child
      seen[n] = 1;
      order.push_back(n);
      const std::vector<int>& children = model_.nodes[n].children;
      for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(static_cast<uint32_t>(*it));
    }
    return order;
  }

  // --- skins ------------------------------------------------------------------------------

  void readSkins() {
    for (size_t k = 0; k < model_.skins.size(); ++k) {
      const tinygltf::Skin& src = model_.skins[k];
      const std::string what = "skin " + std::to_string(k);
      Skin skin;
      skin.name = src.name.empty() ? what : src.name;
      if (src.joints.empty()) fail(what + " has no joints");
      for (const int joint : src.joints) {
        if (joint < 0 || static_cast<size_t>(joint) >= scene_.nodes.size())
          fail(what + " has joint " + std::to_string(joint) + ", which does not exist");
        skin.joints.push_back(static_cast<uint32_t>(joint));
      }
      skin.inverseBindMatrices.assign(skin.joints.size(), glm::mat4(1.0f));
      if (src.inverseBindMatrices >= 0) {
        const std::vector<double> values =
            readAccessor(src.inverseBindMatrices, "inverse bind matrices of " + what, {TINYGLTF_TYPE_MAT4});
        requireFinite(values, "accessor " + std::to_string(src.inverseBindMatrices) + " (inverse bind matrices of " +
                                  what + ")");
        if (values.size() / 16 < skin.joints.size())
          fail(what + " has " + std::to_string(values.size() / 16) + " inverse bind matrices for " +
               std::to_string(skin.joints.size()) + " joints");
        for (size_t j = 0; j < skin.joints.size(); ++j)
          skin.inverseBindMatrices[j] = glm::mat4(glm::make_mat4(values.data() + 16 * j));
      }
      scene_.skins.push_back(std::move(skin));
    }
  }

  // --- materials and textures -------------------------------------------------------------

  static void toRgba8(const tinygltf::Image& image, std::vector<uint8_t>& rgba) {
    const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
    const int components = image.component;
    const bool wide = image.bits == 16;
    rgba.assign(pixels * 4, 255);
    for (size_t p = 0; p < pixels; ++p) {
      uint8_t c[4] = {0, 0, 0, 255};
      for (int k = 0; k < components; ++k) {
        const size_t at = p * static_cast<size_t>(components) + static_cast<size_t>(k);
        c[k] = wide ? static_cast<uint8_t>((readUnaligned<uint16_t>(image.image.data() + at * 2) + 128) / 257)
                    : image.image[at];
      }
      uint8_t* dst = rgba.data() + p * 4;
      if (components <= 2) {  // grey, grey + alpha
        dst[0] = dst[1] = dst[2] = c[0];
        dst[3] = components == 2 ? c[1] : 255;
      } else {
        dst[0] = c[0];
        dst[1] = c[1];
        dst[2] = c[2];
        dst[3] = components == 4 ? c[3] : 255;
      }
    }
  }

  int32_t textureForImage(int imageIndex, const std::string& user) {
    if (imageIndex < 0 || static_cast<size_t>(imageIndex) >= model_.images.size())
      fail(user + " refers to image " + std::to_string(imageIndex) + ", which does not exist");
    if (auto it = textureOfImage_.find(imageIndex); it != textureOfImage_.end()) return it->second;
    const tinygltf::Image& stored = model_.images[static_cast<size_t>(imageIndex)];
    const std::string what =
        "image " + std::to_string(imageIndex) + (stored.uri.empty() ? "" : " (" + stored.uri + ")");
    // Images inside buffer views were left undecoded at parse time (see decodeLater): decode
    // them now that the view is known to lie inside its buffer.
    tinygltf::Image decoded;
    if (stored.image.empty() && stored.bufferView >= 0) {
      const Bytes bytes = viewBytes(stored.bufferView, what);
      if (bytes.size > static_cast<size_t>(std::numeric_limits<int>::max())) fail(what + " is too large");
      decoded = stored;
      std::string err, warning;
      if (!tinygltf::LoadImageData(&decoded, imageIndex, &err, &warning, 0, 0, bytes.data, static_cast<int>(bytes.size),
                                   nullptr))
        fail(what + " could not be decoded: " + oneLine(err));
    }
    const tinygltf::Image& image = decoded.image.empty() ? stored : decoded;
    if (image.image.empty() || image.width <= 0 || image.height <= 0)
      fail(what + " could not be loaded (missing file or undecodable data)");
    if (image.component < 1 || image.component > 4 || (image.bits != 8 && image.bits != 16))
      fail(what + " has an unsupported pixel format");
    const size_t needed = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) *
                          static_cast<size_t>(image.component) * static_cast<size_t>(image.bits / 8);
    if (image.image.size() < needed) fail(what + " has less pixel data than its size says");
    Texture texture;
    texture.name = image.name.empty() ? what : image.name;
    texture.width = static_cast<uint32_t>(image.width);
    texture.height = static_cast<uint32_t>(image.height);
    toRgba8(image, texture.rgba8);
    const int32_t index = static_cast<int32_t>(scene_.textures.size());
    scene_.textures.push_back(std::move(texture));
    textureOfImage_[imageIndex] = index;
    return index;
  }

  void readMaterials() {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& src = model_.materials[i];
      const std::string what = "material " + std::to_string(i);
      Material material;
      material.name = src.name.empty() ? what : src.name;
      material.doubleSided = src.doubleSided;
      const std::vector<double>& factor = src.pbrMetallicRoughness.baseColorFactor;
      if (factor.size() == 4) {
        requireFinite(factor, what + " baseColorFactor");
        material.baseColorFactor = glm::vec4(glm::make_vec4(factor.data()));
      } else if (!factor.empty()) {
        fail(what + " baseColorFactor does not have 4 values");
      }
      const tinygltf::TextureInfo& info = src.pbrMetallicRoughness.baseColorTexture;
      int uvSet = 0;
      if (info.index >= 0) {
        if (static_cast<size_t>(info.index) >= model_.textures.size())
          fail(what + " refers to texture " + std::to_string(info.index) + ", which does not exist");
        const tinygltf::Texture& texture = model_.textures[static_cast<size_t>(info.index)];
        if (texture.source < 0)
          warn(what + ": texture " + std::to_string(info.index) + " has no image we can decode; untextured");
        else
          material.baseColorTexture = textureForImage(texture.source, "texture " + std::to_string(info.index));
        uvSet = std::max(info.texCoord, 0);
      }
      materialUvSet_.push_back(uvSet);
      scene_.materials.push_back(std::move(material));
    }
  }

  uint32_t defaultMaterial() {
    if (!defaultMaterial_) {
      Material material;
      material.name = "default";
      defaultMaterial_ = static_cast<uint32_t>(scene_.materials.size());
      scene_.materials.push_back(material);
      materialUvSet_.push_back(0);
    }
    return *defaultMaterial_;
  }

  // --- meshes -----------------------------------------------------------------------------

  static std::vector<glm::vec3> faceWeightedNormals(const Mesh& mesh) {
    std::vector<glm::vec3> normals(mesh.positions.size(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
      const uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
      // Unnormalized cross product: larger triangles weigh more.
      const glm::vec3 n = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
      normals[a] += n;
      normals[b] += n;
      normals[c] += n;
    }
    for (glm::vec3& n : normals) {
      const float len = glm::length(n);
      n = (len > 0.0f && std::isfinite(len)) ? n / len : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return normals;
  }

  // Triangle list from a triangle primitive's vertex order (glTF 2.0 spec, section 3.7.2.1).
  static std::vector<uint32_t> toTriangleList(int mode, const std::vector<uint32_t>& order) {
    std::vector<uint32_t> out;
    const size_t n = order.size();
    if (mode == TINYGLTF_MODE_TRIANGLES) {
      out.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n - n % 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < n; ++i) {
        const size_t odd = i % 2;
        out.insert(out.end(), {order[i], order[i + 1 + odd], order[i + 2 - odd]});
      }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (size_t i = 0; i + 2 < n; ++i) out.insert(out.end(), {order[i + 1], order[i + 2], order[0]});
    }
    return out;
  }

  std::optional<uint32_t> convertPrimitive(size_t meshIndex, size_t primIndex) {
    const tinygltf::Primitive& prim = model_.meshes[meshIndex].primitives[primIndex];
    const std::string what = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primIndex);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_POINTS) {
      ++scene_.stats.pointPrimitives;
      warn(what + ": points skipped");
      return std::nullopt;
    }
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
      ++scene_.stats.linePrimitives;
      warn(what + ": lines skipped");
      return std::nullopt;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN)
      fail(what + " has unknown mode " + std::to_string(mode));
    ++scene_.stats.trianglePrimitives;

    const auto position = prim.attributes.find("POSITION");
    if (position == prim.attributes.end()) {
      warn(what + ": no POSITION attribute; skipped");
      return std::nullopt;
    }
    Mesh mesh;
    mesh.name =
        (model_.meshes[meshIndex].name.empty() ? "mesh " + std::to_string(meshIndex) : model_.meshes[meshIndex].name) +
        "/" + std::to_string(primIndex);
    const std::vector<double> positions = readAccessor(position->second, "POSITION of " + what, {TINYGLTF_TYPE_VEC3});
    for (size_t i = 0; i < positions.size(); ++i)
      if (!std::isfinite(positions[i]))
        fail("accessor " + std::to_string(position->second) + " (POSITION of " + what +
             ") has a non-finite value at vertex " + std::to_string(i / 3));
    const size_t vertexCount = positions.size() / 3;
    mesh.positions.resize(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v)
      mesh.positions[v] = glm::vec3(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]);

    std::vector<uint32_t> order;
    if (prim.indices >= 0) {
      order = readIndices(prim.indices, "indices of " + what, vertexCount);
    } else {
      order.resize(vertexCount);
      for (size_t v = 0; v < vertexCount; ++v) order[v] = static_cast<uint32_t>(v);
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && order.size() % 3 != 0)
      warn(what + ": index count not a multiple of 3; trailing indices ignored");
    const std::vector<uint32_t> triangles = toTriangleList(mode, order);
    mesh.indices.reserve(triangles.size());
    // A deforming primitive keeps triangles of no area at rest: a morph or a skin may open them.
    const bool deforms = !prim.targets.empty() || prim.attributes.count("JOINTS_0") != 0;
    for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
      const uint32_t a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
      const glm::vec3 area = glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]);
      if (a == b || b == c || a == c || (!deforms && glm::dot(area, area) == 0.0f)) {
        ++scene_.stats.degenerateTriangles;
        continue;
      }
      mesh.indices.insert(mesh.indices.end(), {a, b, c});
    }
    if (mesh.indices.empty()) {
      warn(what + ": no non-degenerate triangles; skipped");
      return std::nullopt;
    }

    if (prim.material >= 0 && static_cast<size_t>(prim.material) >= model_.materials.size())
      fail(what + " refers to material " + std::to_string(prim.material) + ", which does not exist");
    mesh.material = prim.material >= 0 ? static_cast<uint32_t>(prim.material) : defaultMaterial();

    readNormals(prim, what, mesh);
    readSkinInfluences(prim, what, mesh);
    readMorphTargets(prim, what, mesh);
    const std::string uvName = "TEXCOORD_" + std::to_string(materialUvSet_[mesh.material]);
    if (const auto uv = prim.attributes.find(uvName); uv != prim.attributes.end()) {
      const std::vector<double> uvs = readAccessor(uv->second, uvName + " of " + what, {TINYGLTF_TYPE_VEC2});
      if (uvs.size() / 2 != vertexCount) fail(what + ": " + uvName + " count differs from POSITION count");
      requireFinite(uvs, "accessor " + std::to_string(uv->second) + " (" + uvName + " of " + what + ")");
      mesh.uvs.resize(vertexCount);
      for (size_t v = 0; v < vertexCount; ++v) mesh.uvs[v] = glm::vec2(uvs[v * 2], uvs[v * 2 + 1]);
    }

    const uint32_t index = static_cast<uint32_t>(scene_.meshes.size());
    scene_.meshes.push_back(std::move(mesh));
    return index;
  }

  // File normals where usable; generated ones (smooth over shared vertices, so flat for
  // unshared ones) where absent, zero or not finite.
  void readNormals(const tinygltf::Primitive& prim, const std::string& what, Mesh& mesh) {
    const size_t vertexCount = mesh.positions.size();
    const auto normal = prim.attributes.find("NORMAL");
    if (normal == prim.attributes.end()) {
      mesh.normals = faceWeightedNormals(mesh);
      return;
    }
    const std::vector<double> values = readAccessor(normal->second, "NORMAL of " + what, {TINYGLTF_TYPE_VEC3});
    if (values.size() / 3 != vertexCount) fail(what + ": NORMAL count differs from POSITION count");
    mesh.normals.resize(vertexCount);
    std::vector<glm::vec3> generated;
    size_t replaced = 0;
    for (size_t v = 0; v < vertexCount; ++v) {
      const glm::vec3 n(values[v * 3], values[v * 3 + 1], values[v * 3 + 2]);
      const float len = glm::length(n);
      if (len > 1e-12f && std::isfinite(len)) {
        mesh.normals[v] = n / len;
      } else {
        if (generated.empty()) generated = faceWeightedNormals(mesh);
        mesh.normals[v] = generated[v];
        ++replaced;
      }
    }
    if (replaced > 0) warn(what + ": " + std::to_string(replaced) + " invalid normals replaced");
  }

  // JOINTS_n / WEIGHTS_n (n = 0, 1): 4 influences a set. Weights must be finite and not
  // negative; each vertex's are normalized to sum to 1 (exporters leave them a little off, and
  // the blend of joint matrices needs it), and a vertex with no weight follows its first joint.
  void readSkinInfluences(const tinygltf::Primitive& prim, const std::string& what, Mesh& mesh) {
    const size_t vertexCount = mesh.positions.size();
    uint32_t sets = 0;
    while (sets < 2 && prim.attributes.count("JOINTS_" + std::to_string(sets))) ++sets;
    if (sets == 0) {
      if (prim.attributes.count("WEIGHTS_0")) warn(what + ": WEIGHTS_0 without JOINTS_0; not skinned");
      return;
    }
    if (prim.attributes.count("JOINTS_2")) warn(what + ": joint influences past JOINTS_1 ignored");
    std::vector<double> joints, weights;
    for (uint32_t set = 0; set < sets; ++set) {
      const std::string jointsName = "JOINTS_" + std::to_string(set), weightsName = "WEIGHTS_" + std::to_string(set);
      const auto weightsAttribute = prim.attributes.find(weightsName);
      if (weightsAttribute == prim.attributes.end()) fail(what + " has " + jointsName + " but no " + weightsName);
      const int jointsAccessor = prim.attributes.at(jointsName);
      if (jointsAccessor >= 0 && static_cast<size_t>(jointsAccessor) < model_.accessors.size()) {
        const int type = model_.accessors[static_cast<size_t>(jointsAccessor)].componentType;
        if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)
          fail("accessor " + std::to_string(jointsAccessor) + " (" + jointsName + " of " + what +
               ") is not of unsigned byte or short components");
      }
      const std::vector<double> j = readAccessor(jointsAccessor, jointsName + " of " + what, {TINYGLTF_TYPE_VEC4});
      const std::vector<double> w =
          readAccessor(weightsAttribute->second, weightsName + " of " + what, {TINYGLTF_TYPE_VEC4});
      if (j.size() / 4 != vertexCount || w.size() / 4 != vertexCount)
        fail(what + ": " + jointsName + " or " + weightsName + " count differs from POSITION count");
      for (size_t i = 0; i < w.size(); ++i)
        if (!std::isfinite(w[i]) || w[i] < 0.0)
          fail("accessor " + std::to_string(weightsAttribute->second) + " (" + weightsName + " of " + what +
               ") has a negative or non-finite weight at vertex " + std::to_string(i / 4));
      joints.insert(joints.end(), j.begin(), j.end());
      weights.insert(weights.end(), w.begin(), w.end());
    }
    mesh.influences = 4 * sets;
    mesh.joints.resize(vertexCount * mesh.influences);
    mesh.weights.resize(vertexCount * mesh.influences);
    size_t unweighted = 0;
    for (size_t v = 0; v < vertexCount; ++v) {
      double sum = 0.0;
      for (uint32_t set = 0; set < sets; ++set)
        for (size_t c = 0; c < 4; ++c) sum += weights[(set * vertexCount + v) * 4 + c];
      if (!(sum > 0.0)) ++unweighted;
      for (uint32_t set = 0; set < sets; ++set)
        for (size_t c = 0; c < 4; ++c) {
          const size_t from = (set * vertexCount + v) * 4 + c, to = v * mesh.influences + set * 4 + c;
          mesh.weights[to] = sum > 0.0 ? static_cast<float>(weights[from] / sum) : (to % mesh.influences == 0 ? 1.0f : 0.0f);
          // A joint without weight is not read; glTF lets it name any index, so it becomes 0.
          mesh.joints[to] = mesh.weights[to] != 0.0f ? static_cast<uint32_t>(joints[from]) : 0u;
        }
    }
    if (unweighted > 0) warn(what + ": " + std::to_string(unweighted) + " vertices without joint weights follow their first joint");
  }

  // Morph targets' POSITION and NORMAL displacements (other attributes are not rendered).
  void readMorphTargets(const tinygltf::Primitive& prim, const std::string& what, Mesh& mesh) {
    const size_t vertexCount = mesh.positions.size();
    for (size_t k = 0; k < prim.targets.size(); ++k) {
      const std::string target = what + " morph target " + std::to_string(k);
      MorphTarget morph;
      for (const auto& [name, accessor] : prim.targets[k]) {
        if (name != "POSITION" && name != "NORMAL") {
          if (name != "TANGENT") warn(target + ": " + name + " displacements ignored");
          continue;
        }
        const std::vector<double> values = readAccessor(accessor, name + " of " + target, {TINYGLTF_TYPE_VEC3});
        requireFinite(values, "accessor " + std::to_string(accessor) + " (" + name + " of " + target + ")");
        if (values.size() / 3 != vertexCount)
          fail(target + " has " + std::to_string(values.size() / 3) + " " + name + " displacements for " +
               std::to_string(vertexCount) + " vertices");
        std::vector<glm::vec3>& out = name == "POSITION" ? morph.positions : morph.normals;
        out.resize(vertexCount);
        for (size_t v = 0; v < vertexCount; ++v) out[v] = glm::vec3(values[v * 3], values[v * 3 + 1], values[v * 3 + 2]);
      }
      mesh.targets.push_back(std::move(morph));
    }
  }

  // The morph target count of a glTF mesh, the same for all its primitives (glTF requires it),
  // with its default weights checked against it.
  size_t morphTargetCount(int meshIndex) const {
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(meshIndex)];
    const std::string what = "mesh " + std::to_string(meshIndex);
    const size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    for (const tinygltf::Primitive& prim : mesh.primitives)
      if (prim.targets.size() != targets) fail(what + ": its primitives have different numbers of morph targets");
    if (!mesh.weights.empty() && mesh.weights.size() != targets)
      fail(what + " has " + std::to_string(mesh.weights.size()) + " weights for " + std::to_string(targets) +
           " morph targets");
    return targets;
  }

  const std::vector<uint32_t>& meshesOf(int meshIndex, size_t nodeIndex) {
    if (meshIndex < 0 || static_cast<size_t>(meshIndex) >= model_.meshes.size())
      fail("node " + std::to_string(nodeIndex) + " refers to mesh " + std::to_string(meshIndex) +
           ", which does not exist");
    auto [it, inserted] = meshesOfGltfMesh_.try_emplace(meshIndex);
    if (inserted) {
      const size_t primitives = model_.meshes[static_cast<size_t>(meshIndex)].primitives.size();
      for (size_t p = 0; p < primitives; ++p)
        if (auto mesh = convertPrimitive(static_cast<size_t>(meshIndex), p)) it->second.push_back(*mesh);
    }
    return it->second;
  }

  // --- animation --------------------------------------------------------------------------

  void readAnimations() {
    for (size_t a = 0; a < model_.animations.size(); ++a) {
      const tinygltf::Animation& anim = model_.animations[a];
      for (size_t c = 0; c < anim.channels.size(); ++c) {
        const tinygltf::AnimationChannel& src = anim.channels[c];
        const std::string what = "animation " + std::to_string(a) + " channel " + std::to_string(c);
        AnimationChannel channel;
        const std::optional<AnimationPath> path = animationPath(src.target_path);
        if (!path) {
          warn(what + ": " + src.target_path + " animation ignored");
          continue;
        }
        channel.path = *path;
        if (src.target_node < 0) {
          warn(what + ": no target node; ignored");
          continue;
        }
        if (static_cast<size_t>(src.target_node) >= scene_.nodes.size())
          fail(what + " targets node " + std::to_string(src.target_node) + ", which does not exist");
        channel.node = static_cast<uint32_t>(src.target_node);
        if (src.sampler < 0 || static_cast<size_t>(src.sampler) >= anim.samplers.size())
          fail(what + " refers to sampler " + std::to_string(src.sampler) + ", which does not exist");
        const tinygltf::AnimationSampler& sampler = anim.samplers[static_cast<size_t>(src.sampler)];
        const std::optional<Interpolation> interpolation = interpolationOf(sampler.interpolation);
        if (!interpolation) fail(what + " has unknown interpolation " + sampler.interpolation);
        channel.interpolation = *interpolation;

        const std::vector<double> times = readAccessor(sampler.input, "input of " + what, {TINYGLTF_TYPE_SCALAR});
        requireFinite(times, "accessor " + std::to_string(sampler.input) + " (input of " + what + ")");
        const bool rotation = channel.path == AnimationPath::Rotation;
        const bool weights = channel.path == AnimationPath::Weights;
        if (weights) {
          const int mesh = model_.nodes[static_cast<size_t>(src.target_node)].mesh;
          const size_t targets =
              mesh >= 0 && static_cast<size_t>(mesh) < model_.meshes.size() ? morphTargetCount(mesh) : 0;
          if (targets == 0) {
            warn(what + ": weights of a node without morph targets; ignored");
            continue;
          }
          channel.weightCount = static_cast<uint32_t>(targets);
        }
        int components = 0;
        const std::vector<double> values =
            readAccessor(sampler.output, "output of " + what,
                         {weights ? TINYGLTF_TYPE_SCALAR : rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3}, &components);
        requireFinite(values, "accessor " + std::to_string(sampler.output) + " (output of " + what + ")");
        const size_t perKey = channel.interpolation == Interpolation::CubicSpline ? 3 : 1;
        if (weights) components = static_cast<int>(channel.weightCount);  // one element per weight
        if (times.empty()) {
          warn(what + ": no keys; ignored");
          continue;
        }
        if (values.size() / static_cast<size_t>(components) != times.size() * perKey)
          fail(what + ": output count does not match " + std::to_string(times.size()) + " keys");

        // Keys must increase; equal times (seen in exported files) keep the later key.
        for (size_t k = 0; k < times.size(); ++k) {
          if (k + 1 < times.size() && times[k + 1] < times[k]) fail(what + ": key times decrease");
          if (k + 1 < times.size() && times[k + 1] == times[k]) continue;
          channel.times.push_back(static_cast<float>(times[k]));
          for (size_t j = 0; j < perKey; ++j) {
            const size_t e = (k * perKey + j) * static_cast<size_t>(components);
            if (weights)
              channel.weights.insert(channel.weights.end(), values.begin() + static_cast<std::ptrdiff_t>(e),
                                     values.begin() + static_cast<std::ptrdiff_t>(e + channel.weightCount));
            else
              channel.values.emplace_back(values[e], values[e + 1], values[e + 2], rotation ? values[e + 3] : 0.0);
          }
        }
        if (channel.times.size() < times.size()) warn(what + ": keys with repeated times dropped");
        scene_.channels.push_back(std::move(channel));
      }
    }
    if (!scene_.channels.empty()) {
      float first = scene_.channels[0].times.front(), last = scene_.channels[0].times.back();
      for (const AnimationChannel& ch : scene_.channels) {
        first = std::min(first, ch.times.front());
        last = std::max(last, ch.times.back());
      }
      scene_.settings.frameTime = 0.5f * (first + last);
    }
  }

  // --- what the scene shows ---------------------------------------------------------------

  void readCamera(const tinygltf::Node& node, uint32_t nodeIndex) {
    if (node.camera < 0) return;
    if (static_cast<size_t>(node.camera) >= model_.cameras.size())
      fail("node " + std::to_string(nodeIndex) + " refers to camera " + std::to_string(node.camera) +
           ", which does not exist");
    const tinygltf::Camera& src = model_.cameras[static_cast<size_t>(node.camera)];
    const std::string what = "camera " + std::to_string(node.camera);
    if (src.type != "perspective") {
      warn(what + ": " + src.type + " cameras are not supported; ignored");
      return;
    }
    if (scene_.camera) return;  // the first one wins
    const tinygltf::PerspectiveCamera& p = src.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.14159) || !(p.aspectRatio >= 0.0) || !(p.znear >= 0.0) || !(p.zfar >= 0.0) ||
        !finiteAsFloat(p.aspectRatio) || !finiteAsFloat(p.znear) || !finiteAsFloat(p.zfar))
      fail(what + " has invalid perspective parameters");
    Camera camera;
    camera.node = static_cast<int32_t>(nodeIndex);
    camera.yfov = static_cast<float>(p.yfov);
    camera.aspectRatio = static_cast<float>(p.aspectRatio);
    camera.znear = static_cast<float>(p.znear);
    camera.zfar = static_cast<float>(p.zfar);
    if (camera.zfar != 0.0f && !(camera.zfar > camera.znear)) {
      warn(what + ": zfar not beyond znear; derived instead");
      camera.zfar = 0.0f;
    }
    scene_.camera = camera;
  }

  void readLight(const tinygltf::Node& node, uint32_t nodeIndex) {
    const auto ext = node.extensions.find("KHR_lights_punctual");
    if (ext == node.extensions.end() || !ext->second.IsObject() || !ext->second.Has("light")) return;
    const tinygltf::Value& ref = ext->second.Get("light");
    const int lightIndex = ref.IsNumber() ? ref.GetNumberAsInt() : -1;
    if (lightIndex < 0 || static_cast<size_t>(lightIndex) >= model_.lights.size())
      fail("node " + std::to_string(nodeIndex) + " refers to light " + std::to_string(lightIndex) +
           ", which does not exist");
    const tinygltf::Light& light = model_.lights[static_cast<size_t>(lightIndex)];
    if (light.type != "directional") {
      warn("light " + std::to_string(lightIndex) + ": " + light.type + " lights are not supported; ignored");
      return;
    }
    if (haveLight_) return;
    glm::vec3 color(1.0f);
    if (light.color.size() == 3 && allFinite(light.color)) color = glm::vec3(glm::make_vec3(light.color.data()));
    const float intensity = finiteAsFloat(light.intensity) ? static_cast<float>(light.intensity) : 1.0f;
    const glm::mat4 world = scene_.worldMatrixAt(nodeIndex, scene_.settings.frameTime);
    const glm::vec3 direction(world * glm::vec4(0.0f, 0.0f, -1.0f, 0.0f));
    const float len = glm::length(direction);
    if (!(len > 0.0f) || !std::isfinite(len)) {
      warn("light " + std::to_string(lightIndex) + ": degenerate direction; ignored");
      return;
    }
    scene_.light.direction = direction / len;
    scene_.light.color = color * intensity;
    haveLight_ = true;
  }

  void placeContent() {
    readMaterials();
    uint32_t nextObjectId = 1;
    for (uint32_t nodeIndex : sceneNodesInOrder()) {
      const tinygltf::Node& node = model_.nodes[nodeIndex];
      if (node.mesh >= 0) {
        const std::vector<uint32_t>& meshes = meshesOf(node.mesh, nodeIndex);
        for (uint32_t mesh : meshes) scene_.instances.push_back(deformingInstance(node, nodeIndex, mesh, nextObjectId));
        if (!meshes.empty()) ++nextObjectId;
      }
      readCamera(node, nodeIndex);
      readLight(node, nodeIndex);
    }
    giveDeformingInstancesTheirOwnMeshes();
  }

  // The instance of one of a node's meshes, with what deforms it: the node's skin when the mesh
  // has joint influences (the instance then sits on an identity root of its own, since glTF
  // ignores the transform of a skinned mesh's node), and the node's weights when it has morph
  // targets.
  Instance deformingInstance(const tinygltf::Node& node, uint32_t nodeIndex, uint32_t mesh, uint32_t objectId) {
    Instance instance{mesh, nodeIndex, objectId};
    const std::string what = "node " + std::to_string(nodeIndex);
    const Mesh& m = scene_.meshes[mesh];
    if (node.skin >= 0 && static_cast<size_t>(node.skin) >= scene_.skins.size())
      fail(what + " refers to skin " + std::to_string(node.skin) + ", which does not exist");
    if (node.skin >= 0 && m.influences > 0) {
      const Skin& skin = scene_.skins[static_cast<size_t>(node.skin)];
      const auto worst = std::max_element(m.joints.begin(), m.joints.end());
      if (*worst >= skin.joints.size())
        fail(m.name + " names joint " + std::to_string(*worst) + " of skin " + std::to_string(node.skin) +
             ", which has " + std::to_string(skin.joints.size()));
      instance.skin = node.skin;
      auto [root, added] = skinnedRoot_.try_emplace(nodeIndex, static_cast<uint32_t>(scene_.nodes.size()));
      if (added) {
        Node identity;
        identity.name = scene_.nodes[nodeIndex].name + " (skinned)";
        scene_.nodes.push_back(std::move(identity));
      }
      instance.node = root->second;
    } else if (node.skin >= 0) {
      warn(what + ": skin " + std::to_string(node.skin) + " on a mesh without joint influences; not skinned");
    } else if (m.influences > 0) {
      warn(what + ": " + m.name + " has joint influences but the node has no skin; drawn in its bind pose");
    }
    if (!m.targets.empty()) {
      const size_t targets = morphTargetCount(node.mesh);
      std::vector<float>& weights = scene_.nodes[nodeIndex].weights;
      if (weights.empty()) {
        const std::vector<double>& meshWeights = model_.meshes[static_cast<size_t>(node.mesh)].weights;
        requireFinite(meshWeights, "mesh " + std::to_string(node.mesh) + " weights");
        weights.assign(meshWeights.begin(), meshWeights.end());
      } else if (weights.size() != targets) {
        fail(what + " has " + std::to_string(weights.size()) + " weights for " + std::to_string(targets) +
             " morph targets");
      }
      instance.morphNode = static_cast<int32_t>(nodeIndex);
    }
    return instance;
  }

  // A deforming instance changes its mesh's vertices on the device, so it must not share them:
  // every mesh used by a deforming instance and by others is copied for each deforming one
  // but the last. What the copies and their targets hold is capped, as an accessor is: a small
  // file naming one large mesh from many nodes cannot exhaust memory.
  void giveDeformingInstancesTheirOwnMeshes() {
    std::vector<uint32_t> uses(scene_.meshes.size(), 0);
    for (const Instance& instance : scene_.instances) ++uses[instance.mesh];
    uint64_t deformedElements = 0;
    for (Instance& instance : scene_.instances) {
      if (!instance.deforms()) continue;
      const Mesh& mesh = scene_.meshes[instance.mesh];
      deformedElements += uint64_t(mesh.positions.size()) * (1 + mesh.targets.size());
      if (deformedElements > kMaxElements)
        fail("deforms more than " + std::to_string(kMaxElements) + " vertices and target displacements in all");
      if (uses[instance.mesh] <= 1) continue;
      --uses[instance.mesh];
      Mesh copy = mesh;
      instance.mesh = static_cast<uint32_t>(scene_.meshes.size());
      scene_.meshes.push_back(std::move(copy));
      uses.push_back(1);
    }
  }

  const fs::path& path_;
  const tinygltf::Model& model_;
  Scene scene_;
  std::map<int, int32_t> textureOfImage_;
  std::map<int, std::vector<uint32_t>> meshesOfGltfMesh_;
  std::map<uint32_t, uint32_t> skinnedRoot_;  // per skinned node, its identity root
  std::vector<int> materialUvSet_;
  std::optional<uint32_t> defaultMaterial_;
  bool haveLight_ = false;
};

// tinygltf hands an image's buffer view to the decoder without checking that the view lies
// inside its buffer, so a corrupt file could make the decoder read out of bounds. Images in
// buffer views are therefore decoded later, after validation; images from URIs (bytes that
// tinygltf read itself) are decoded as usual.
bool decodeLater(tinygltf::Image* image, const int imageIndex, std::string* err, std::string* warn, int width,
                 int height, const unsigned char* bytes, int size, void* userData) {
  if (image->bufferView >= 0) return true;
  return tinygltf::LoadImageData(image, imageIndex, err, warn, width, height, bytes, size, userData);
}

bool looksBinary(const fs::path& path) {
  const std::string ext = toLower(path.extension().string());
  if (ext == ".glb") return true;
  if (ext == ".gltf") return false;
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  in.read(magic, 4);
  return in.gcount() == 4 && std::memcmp(magic, "glTF", 4) == 0;
}

// The binary container's version, which the parser does not check: only 2 is glTF 2.0.
void requireGlbVersion2(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char header[8] = {};
  in.read(reinterpret_cast<char*>(header), sizeof(header));
  if (in.gcount() < 8) return;  // too short: the parser says so
  const uint32_t version = header[4] | header[5] << 8 | header[6] << 16 | uint32_t(header[7]) << 24;
  if (version != 2)
    throw Error(path.string() + ": binary glTF version " + std::to_string(version) +
                (version == 1 ? " (glTF 1.0)" : "") + "; only glTF 2.0 is supported");
}

// The file's JSON (a .gltf, or a .glb's first chunk), or null where it is not JSON (the parser
// then says why). Read at most 256 MiB: no real scene description is larger.
nlohmann::json fileJson(const fs::path& path, bool binary) {
  constexpr uint64_t kMaxJsonBytes = uint64_t{256} << 20;
  std::ifstream in(path, std::ios::binary);
  uint64_t length = 0;
  if (binary) {
    unsigned char header[20] = {};
    in.read(reinterpret_cast<char*>(header), sizeof(header));
    if (in.gcount() < 20 || std::memcmp(header + 16, "JSON", 4) != 0) return nullptr;
    length = header[12] | header[13] << 8 | header[14] << 16 | uint64_t(header[15]) << 24;
  } else {
    std::error_code ec;
    length = fs::file_size(path, ec);
    if (ec) return nullptr;
  }
  if (length > kMaxJsonBytes) return nullptr;
  std::string text(length, '\0');
  in.read(text.data(), static_cast<std::streamsize>(length));
  text.resize(static_cast<size_t>(in.gcount()));
  return nlohmann::json::parse(text, nullptr, false);
}

// Refuses, with the reason, files of another glTF version and files that require an extension
// this loader does not implement.
void refuseWhatCannotLoad(const fs::path& path, const std::string& version, const std::vector<std::string>& required) {
  if (version.empty())
    throw Error(path.string() + ": no asset version (a glTF 1.0 file?); only glTF 2.0 is supported");
  if (version.rfind("2.", 0) != 0 && version != "2")
    throw Error(path.string() + ": a glTF " + version + " file; only glTF 2.0 is supported");
  for (const std::string& ext : required) {
    if (implementedExtension(ext)) continue;
    if (ext == "KHR_draco_mesh_compression")
      throw Error(path.string() + ": requires KHR_draco_mesh_compression (Draco-compressed geometry), which this "
                                  "loader does not decode; export it uncompressed");
    throw Error(path.string() + ": requires extension " + ext + ", which this loader does not implement");
  }
}

// Where the parser failed, the file's own JSON says whether the reason is one of the above: a
// glTF 1.0 layout, or Draco's compressed accessors, which have no buffer view (the parser
// reports "invalid bufferView"). Returns when the JSON shows neither.
void explainParseFailure(const fs::path& path, bool binary) {
  const nlohmann::json json = fileJson(path, binary);
  if (!json.is_object()) return;
  std::string version;
  const auto asset = json.find("asset");
  if (asset != json.end() && asset->is_object()) {
    const auto v = asset->find("version");
    if (v != asset->end() && v->is_string()) version = v->get<std::string>();
    if (v != asset->end() && v->is_number()) version = v->dump();
  }
  std::vector<std::string> required;
  const auto listed = json.find("extensionsRequired");
  if (listed != json.end() && listed->is_array())
    for (const nlohmann::json& entry : *listed)
      if (entry.is_string()) required.push_back(entry.get<std::string>());
  refuseWhatCannotLoad(path, version, required);
}

}  // namespace

Scene loadGltf(const std::filesystem::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw Error(path.string() + ": no such file");
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  const bool binary = looksBinary(path);
  if (binary) requireGlbVersion2(path);
  try {
    tinygltf::TinyGLTF parser;
    parser.SetImageLoader(&decodeLater, nullptr);
    ok = binary ? parser.LoadBinaryFromFile(&model, &err, &warn, path.string())
                : parser.LoadASCIIFromFile(&model, &err, &warn, path.string());
  } catch (const std::exception& e) {
    explainParseFailure(path, binary);
    throw Error(path.string() + ": " + oneLine(e.what()));
  }
  if (!ok) {
    explainParseFailure(path, binary);
    throw Error(path.string() + ": " + (err.empty() ? std::string("not a valid glTF file") : oneLine(err)));
  }
  // A file the parser read may still be one of another version, or need what is not here.
  refuseWhatCannotLoad(path, model.asset.version, model.extensionsRequired);

  GltfImporter importer(path, model);
  Scene scene;
  try {
    scene = importer.run();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // e.g. out of memory on a hostile file
    importer.fail(oneLine(e.what()));
  }
  if (!warn.empty()) scene.stats.warnings.insert(scene.stats.warnings.begin(), oneLine(warn));
  return scene;
}

}  // namespace hmb::scene
