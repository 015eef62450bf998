// The scene model: what every method renders. Meshes, materials, a node hierarchy with TRS
// animation that can be sampled at any time, instances that carry an object id, a camera,
// a directional light, and the per-scene motion-blur settings.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "hmblur/aabb.h"

namespace hmb::scene {

struct Texture {
  std::string name;
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba8;  // width * height * 4, sRGB-encoded base colour
};

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};  // linear RGBA
  int32_t baseColorTexture = -1;    // index into Scene::textures, -1 when untextured
  bool doubleSided = false;         // glTF: back faces are culled unless set
};

// One glTF morph target: displacements added to the mesh's vertices, scaled by the target's
// weight. Either list may be empty (the target moves nothing of that kind).
struct MorphTarget {
  std::vector<glm::vec3> positions;  // per vertex
  std::vector<glm::vec3> normals;    // per vertex
};

// One triangle list with one material (a glTF primitive). Positions are in the mesh's own space.
struct Mesh {
  std::string name;
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // per vertex, same count as positions (generated if absent)
  std::vector<glm::vec2> uvs;      // per vertex or empty
  std::vector<uint32_t> indices;   // 3 per triangle
  uint32_t material = 0;           // index into Scene::materials
  // Skin influences (glTF JOINTS_n / WEIGHTS_n): `influences` per vertex, 0 (not skinned), 4
  // or 8; joints index the instance's Skin::joints, and each vertex's weights sum to 1 (the
  // loader normalizes them).
  uint32_t influences = 0;
  std::vector<uint32_t> joints;
  std::vector<float> weights;
  std::vector<MorphTarget> targets;
  uint32_t triangleCount() const { return static_cast<uint32_t>(indices.size() / 3); }
};

// A glTF skin: the joint nodes, and the matrix taking each joint's bind pose to its space.
struct Skin {
  std::string name;
  std::vector<uint32_t> joints;                 // node indices
  std::vector<glm::mat4> inverseBindMatrices;   // per joint
};

// A node's local transform: translation, rotation, scale (glTF order T * R * S).
struct Trs {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // w, x, y, z
  glm::vec3 scale{1.0f};
  glm::mat4 matrix() const;
};

struct Node {
  std::string name;
  int32_t parent = -1;  // index into Scene::nodes, -1 for a root
  Trs local;            // rest transform, overridden per channel by animation
  std::vector<float> weights;  // rest morph weights of its mesh's targets (node's, else mesh's)
};

enum class AnimationPath { Translation, Rotation, Scale, Weights };
enum class Interpolation { Step, Linear, CubicSpline };

// One animated property of one node. For CubicSpline, values holds (in-tangent, value,
// out-tangent) triples per key, as in glTF. Rotations are stored as (x, y, z, w). Morph
// weights (path Weights) are in `weights` instead: weightCount per element, the same layout.
struct AnimationChannel {
  uint32_t node = 0;
  AnimationPath path = AnimationPath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;  // seconds, strictly increasing
  std::vector<glm::vec4> values;
  uint32_t weightCount = 0;
  std::vector<float> weights;
};

// Where time t falls among a channel's keys: the segment k0..k1 = k0 + 1 at fraction u of
// its dt seconds, or k0 == k1 before the first key or from the last one on (also for NaN).
struct KeySegment {
  size_t k0 = 0, k1 = 0;
  float u = 0.0f, dt = 0.0f;
};
KeySegment keySegment(const std::vector<float>& times, float t);

// glTF's cubic spline from key value v0 to v1 at fraction u of a segment of dt seconds; the
// tangents are per second, so they scale with the key spacing.
template <class T>
T cubicSpline(const T& v0, const T& outTangent0, const T& v1, const T& inTangent1, float u, float dt) {
  const float u2 = u * u, u3 = u2 * u;
  return (2.0f * u3 - 3.0f * u2 + 1.0f) * v0 + (u3 - 2.0f * u2 + u) * dt * outTangent0 +
         (-2.0f * u3 + 3.0f * u2) * v1 + (u3 - u2) * dt * inTangent1;
}

// Draws one mesh with the world transform of one node. Instances of the same node share
// an object id: the id names an object, not a draw.
// A deforming instance (skinned, or with morph targets) has a mesh of its own. A skinned one
// sits on an identity root node, as glTF ignores the transform of a skinned mesh's node.
struct Instance {
  uint32_t mesh = 0;
  uint32_t node = 0;
  uint32_t objectId = 0;
  int32_t skin = -1;       // index into Scene::skins when the mesh is skinned
  int32_t morphNode = -1;  // the node whose weights drive the mesh's morph targets, when it has any
  bool deforms() const { return skin >= 0 || morphNode >= 0; }
};

struct Camera {
  int32_t node = -1;              // the camera looks down the node's -Z, +Y up (glTF)
  float yfov = 0.8f;              // radians
  float aspectRatio = 0.0f;       // 0: taken from the image size
  float znear = 0.0f;             // 0: derived from the scene (see deriveDefaults)
  float zfar = 0.0f;              // 0: derived from the scene
};

struct DirectionalLight {
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // direction the light travels, world space, unit
  glm::vec3 color{1.0f};                   // linear, intensity folded in
  glm::vec3 ambient{0.15f};                // constant ambient term
};

// Per-scene settings of the technique (paper, section 4). A value <= 0 means "derive from
// the scene" where the comment says so.
struct Settings {
  float softZExtent = 0.0f;     // SOFT_Z_EXTENT in scene units; <= 0: derived from scene scale
  float edgeThreshold = 0.9f;   // ray-mask edge threshold e
  float fps = 120.0f;           // frame rate; the previous frame is at t - 1/fps
  float exposure = 1.0f / 60.0f;// shutter open over [t - exposure, t]
  float frameTime = 0.0f;       // t_k: the default time rendered
};

// What the loader left out, so reports can say it.
struct LoadStats {
  uint32_t trianglePrimitives = 0;
  uint32_t linePrimitives = 0;   // skipped: not rendered
  uint32_t pointPrimitives = 0;  // skipped: not rendered
  uint32_t degenerateTriangles = 0;
  std::vector<std::string> warnings;
};

struct Scene {
  std::string name;
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<Node> nodes;
  std::vector<Skin> skins;
  std::vector<AnimationChannel> channels;
  std::vector<Instance> instances;
  std::optional<Camera> camera;  // none: deriveDefaults places one
  DirectionalLight light;
  // What a ray that hits nothing sees, and the raster where no surface is: linear colour.
  glm::vec3 background{0.0f};
  Settings settings;
  LoadStats stats;

  // Local transform of a node at time t (seconds): its rest TRS with every animation channel
  // that targets it sampled at t (clamped to the channel's key range).
  Trs localTrsAt(uint32_t node, float t) const;
  // World matrix of a node at time t: the product of local transforms up to the root.
  glm::mat4 worldMatrixAt(uint32_t node, float t) const;
  // True when any channel targets the node or one of its ancestors.
  bool isAnimated(uint32_t node) const;
  // World-space bounds of every instance at time t (deforming ones deformed at t).
  Aabb boundsAt(float t) const;
  // Whether any instance deforms (scenes/deformation.h).
  bool hasDeformation() const;
  uint64_t triangleCount() const;
};

// Rotation whose -Z axis (the camera's view direction) points along `forward`, with +Y as
// close to world up as possible.
glm::quat lookRotation(const glm::vec3& forward);

// A scene of one mesh (these triangles, flat normals left to the loader's defaults: +z) drawn
// once at the identity as object 1: how tests and benchmarks trace plain triangle lists.
Scene singleMeshScene(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices);

// Fills in what the scene left open, from the scene itself (never from fixed constants): a
// camera framing the bounds when none is given, near/far from the bounds seen from the
// camera, SOFT_Z_EXTENT from the scene's scale.
void deriveDefaults(Scene& scene);

}  // namespace hmb::scene
