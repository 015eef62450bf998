#include "runtime/device_scene/gpu_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>

#include "hmblur/error.h"
#include "hmblur/image.h"
#include "runtime/device_scene/deformed_vertices.h"
#include "runtime/vulkan/frame_recorder.h"
#include "scenes/deformation.h"

namespace hmb {
namespace {

glm::mat4 cameraWorld(const scene::Scene& scene, float t) {
  if (!scene.camera || scene.camera->node < 0) return glm::mat4(1.0f);
  return scene.worldMatrixAt(static_cast<uint32_t>(scene.camera->node), t);
}

struct DepthRange {
  float znear, zfar;
};

DepthRange depthRange(const scene::Scene& scene) {
  const scene::Camera camera = scene.camera.value_or(scene::Camera{});
  const float znear = camera.znear > 0.0f ? camera.znear : 0.1f;
  return {znear, camera.zfar > znear ? camera.zfar : znear * 1000.0f};
}

glm::mat4 projection(const scene::Scene& scene, uint32_t width, uint32_t height) {
  const scene::Camera camera = scene.camera.value_or(scene::Camera{});
  const float aspect = camera.aspectRatio > 0.0f ? camera.aspectRatio : float(width) / float(height);
  const DepthRange range = depthRange(scene);
  // Reversed depth: z/w = n (f - d) / ((f - n) d) at camera distance d, 1 at the near plane and
  // 0 at the far one. Float has its finest steps near 0, where perspective crowds distant
  // surfaces, so a near/far ratio of 1e9 still keeps surfaces a part in 1e6 apart (the
  // standard mapping, 1 - n/d near the far end, loses them past a ratio of about 1e4).
  const float n = range.znear, f = range.zfar;
  glm::mat4 p(0.0f);
  p[0][0] = 1.0f / (aspect * std::tan(camera.yfov * 0.5f));
  p[1][1] = -1.0f / std::tan(camera.yfov * 0.5f);  // Vulkan clip space: y points down the image
  p[2][2] = n / (f - n);                            // z_clip = n (f - d) / (f - n), with z_view = -d
  p[3][2] = n * f / (f - n);
  p[2][3] = -1.0f;                                  // w_clip = d
  return p;
}

}  // namespace

FrameCamera frameCamera(const scene::Scene& scene, float t, uint32_t width, uint32_t height) {
  FrameCamera camera;
  const float previous = t - 1.0f / scene.settings.fps;
  const glm::mat4 worldNow = cameraWorld(scene, t);
  camera.view = glm::inverse(worldNow);
  camera.projection = projection(scene, width, height);
  camera.viewProjCurrent = camera.projection * camera.view;
  camera.viewProjPrevious = camera.projection * glm::inverse(cameraWorld(scene, previous));
  camera.eye = glm::vec3(worldNow[3]);
  const DepthRange range = depthRange(scene);
  camera.znear = range.znear;
  camera.zfar = range.zfar;
  return camera;
}

std::vector<gpu::GpuShutterClip> shutterClips(const scene::Scene& scene, float t, float exposure, uint32_t width,
                                              uint32_t height) {
  const glm::mat4 projection = frameCamera(scene, t, width, height).projection;
  const float mid = t - 0.5f * exposure, open = t - exposure;
  const glm::mat4 viewProjMid = projection * glm::inverse(cameraWorld(scene, mid));
  const glm::mat4 viewProjOpen = projection * glm::inverse(cameraWorld(scene, open));
  std::vector<gpu::GpuShutterClip> clips;
  for (const scene::Instance& instance : scene.instances)
    clips.push_back({viewProjMid * scene.worldMatrixAt(instance.node, mid),
                     viewProjOpen * scene.worldMatrixAt(instance.node, open)});
  return clips;
}

bool cameraMovesOnScreen(const scene::Scene& scene, float t) {
  return cameraWorld(scene, t) != cameraWorld(scene, t - 1.0f / scene.settings.fps);
}

bool anythingMovesOnScreen(const scene::Scene& scene, float t) {
  const float previous = t - 1.0f / scene.settings.fps;
  if (cameraMovesOnScreen(scene, t)) return true;
  return std::any_of(scene.instances.begin(), scene.instances.end(), [&](const scene::Instance& instance) {
    return scene.worldMatrixAt(instance.node, t) != scene.worldMatrixAt(instance.node, previous) ||
           (instance.deforms() && scene::deformationDiffers(scene, instance, t, previous));
  });
}

GpuScene::GpuScene(const vk::Context& context, const scene::Scene& scene)
    : topLevelWalk_(scene.instances.size() != 1) {
  std::vector<gpu::GpuVertex> vertices;
  std::vector<uint32_t> meshVertexBase;
  for (const scene::Mesh& mesh : scene.meshes) {
    meshVertexBase.push_back(static_cast<uint32_t>(vertices.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      gpu::GpuVertex v{};
      v.position = glm::vec4(mesh.positions[i], 1.0f);
      v.normal = glm::vec4(i < mesh.normals.size() ? mesh.normals[i] : glm::vec3(0.0f, 0.0f, 1.0f), 0.0f);
      v.uv = i < mesh.uvs.size() ? mesh.uvs[i] : glm::vec2(0.0f);
      vertices.push_back(v);
    }
  }

  // Each instance gets its own copy of its mesh's vertex indices and triangles, so kernels
  // address transformed vertices without indirection.
  std::vector<gpu::GpuInstanceVertex> instanceVertices;
  std::vector<gpu::GpuTriangle> triangles;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Mesh& mesh = scene.meshes.at(scene.instances[i].mesh);
    const auto base = static_cast<uint32_t>(instanceVertices.size());
    for (uint32_t v = 0; v < mesh.positions.size(); ++v)
      instanceVertices.push_back({meshVertexBase[scene.instances[i].mesh] + v, i});
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      triangles.push_back({base + mesh.indices[t], base + mesh.indices[t + 1], base + mesh.indices[t + 2], i});
  }
  if (triangles.size() >= 0x7fffffffu) throw Error("scene has more triangles than one frame can address");
  triangleCount_ = static_cast<uint32_t>(triangles.size());
  instanceVertexCount_ = static_cast<uint32_t>(instanceVertices.size());

  std::vector<gpu::GpuMaterial> materials;
  // Texels are decoded from sRGB here, once, and kept as linear half floats (two words each:
  // red and green, blue and alpha), so that shading samples four of them with no pow() per
  // pixel (shared/shading.glsl). Half floats hold every decoded 8-bit value within 5e-4
  // relative, far inside one 8-bit step.
  std::vector<uint32_t> texels;
  std::vector<uint32_t> textureOffset;  // in texels
  // 256 codes: decoded once each, not once per texel.
  std::array<float, 256> decode{};
  for (size_t code = 0; code < decode.size(); ++code) decode[code] = float(io::srgbToLinear(code / 255.0));
  for (const scene::Texture& texture : scene.textures) {
    textureOffset.push_back(static_cast<uint32_t>(texels.size() / 2));
    const size_t count = size_t(texture.width) * texture.height;
    for (size_t t = 0; t < count; ++t) {
      uint8_t rgba[4] = {0, 0, 0, 0};
      if (4 * t + 3 < texture.rgba8.size()) std::memcpy(rgba, texture.rgba8.data() + 4 * t, 4);
      texels.push_back(glm::packHalf2x16(glm::vec2(decode[rgba[0]], decode[rgba[1]])));
      texels.push_back(glm::packHalf2x16(glm::vec2(decode[rgba[2]], rgba[3] / 255.0f)));
    }
  }
  // Kernels read the texels two to a 16-byte record (shared/scene_bindings.glsl).
  texels.resize(std::max<size_t>(4, (texels.size() + 3) / 4 * 4));
  for (const scene::Material& m : scene.materials) {
    gpu::GpuMaterial g{};
    g.baseColor = m.baseColorFactor;
    g.textureOffset = HMB_NO_TEXTURE;
    if (m.baseColorTexture >= 0 && size_t(m.baseColorTexture) < scene.textures.size()) {
      const scene::Texture& texture = scene.textures[m.baseColorTexture];
      if (texture.width > 0 && texture.height > 0) {
        g.textureOffset = textureOffset[m.baseColorTexture];
        g.textureWidth = texture.width;
        g.textureHeight = texture.height;
        texturePath_ = true;
      }
    }
    materials.push_back(g);
  }

  data_ = std::make_shared<Data>();
  data_->vertices = vk::uploadedBuffer(context, vertices, "scene vertices");
  data_->instanceVertices = vk::uploadedBuffer(context, instanceVertices, "instance vertices");
  data_->triangles = vk::uploadedBuffer(context, triangles, "triangles");
  data_->materials = vk::uploadedBuffer(context, materials, "materials");
  data_->texels = vk::uploadedBuffer(context, texels, "texels");
  instances_ = vk::Buffer(context, std::max<size_t>(1, scene.instances.size()) * sizeof(gpu::GpuInstance),
                          vk::MemoryUse::Device, "instances");
  cameraBuffer_ = vk::Buffer(context, sizeof(gpu::GpuCamera), vk::MemoryUse::Device, "camera");
  if (scene.hasDeformation()) {
    deformation_ = std::make_unique<DeformedVertices>(context, scene, meshVertexBase);
    previousVertices_ = vk::uploadedBuffer(context, vertices, "scene vertices (previous frame)");
  }
}

GpuScene::GpuScene(const vk::Context& context, const GpuScene& sharesDataOf)
    : triangleCount_(sharesDataOf.triangleCount_),
      instanceVertexCount_(sharesDataOf.instanceVertexCount_),
      texturePath_(sharesDataOf.texturePath_),
      topLevelWalk_(sharesDataOf.topLevelWalk_),
      camera_(sharesDataOf.camera_),
      data_(sharesDataOf.data_) {
  if (sharesDataOf.deforms()) throw Error("a deforming scene's vertices are written each frame: they are not shared");
  instances_ = vk::Buffer(context, sharesDataOf.instances_.size(), vk::MemoryUse::Device, "instances");
  cameraBuffer_ = vk::Buffer(context, sizeof(gpu::GpuCamera), vk::MemoryUse::Device, "camera");
}

GpuScene::GpuScene(GpuScene&&) noexcept = default;
GpuScene::~GpuScene() = default;

void GpuScene::recordFrameDeformation(vk::FrameRecorder& frame) const {
  if (!deformation_) return;
  deformation_->record(frame, DeformedVertices::kPreviousSlot, previousVertices_);
  if (!verticesAtFrameTime_) deformation_->record(frame, DeformedVertices::kFrameSlot, data_->vertices);
}

void GpuScene::recordDeformationAt(const scene::Scene& scene, float t, vk::FrameRecorder& frame) {
  if (!deformation_) return;
  deformation_->setTime(scene, DeformedVertices::kAnyTimeSlot, t);
  deformation_->record(frame, DeformedVertices::kAnyTimeSlot, data_->vertices);
  verticesAtFrameTime_ = t == frameTime_;
}

void GpuScene::bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const {
  static_assert(sizeof(gpu::SceneTable) == 5 * sizeof(uint64_t));
  const vk::Buffer* members[] = {&data_->vertices, &instances_, &data_->materials, &data_->texels, &cameraBuffer_};  // SceneTable's order
  shading_.bind(bindings, firstBinding, byAddress, members);
}

GpuScene::FrameInputs GpuScene::frameInputs(const scene::Scene& scene, float t, uint32_t width, uint32_t height) {
  const float previous = t - 1.0f / scene.settings.fps;
  FrameInputs inputs;
  for (const scene::Instance& instance : scene.instances) {
    gpu::GpuInstance g{};
    g.worldCurrent = scene.worldMatrixAt(instance.node, t);
    g.worldPrevious = scene.worldMatrixAt(instance.node, previous);
    g.normalCurrent = glm::transpose(glm::inverse(g.worldCurrent));
    g.objectId = instance.objectId;
    const scene::Mesh& mesh = scene.meshes.at(instance.mesh);
    g.material = mesh.material;
    const bool doubleSided = mesh.material < scene.materials.size() && scene.materials[mesh.material].doubleSided;
    g.flags = doubleSided ? HMB_INSTANCE_DOUBLE_SIDED : 0u;
    inputs.instances.push_back(g);
  }
  inputs.camera = frameCamera(scene, t, width, height);
  gpu::GpuCamera& c = inputs.gpuCamera;
  c.viewProjCurrent = inputs.camera.viewProjCurrent;
  c.viewProjPrevious = inputs.camera.viewProjPrevious;
  c.viewCurrent = inputs.camera.view;
  c.positionCurrent = glm::vec4(inputs.camera.eye, 1.0f);
  c.lightDirection = glm::vec4(glm::normalize(scene.light.direction), 0.0f);
  c.lightColor = glm::vec4(scene.light.color, 0.0f);
  c.ambient = glm::vec4(scene.light.ambient, 0.0f);
  c.background = glm::vec4(scene.background, 1.0f);
  return inputs;
}

void GpuScene::setFrame(const scene::Scene& scene, float t, uint32_t width, uint32_t height) {
  const FrameInputs inputs = frameInputs(scene, t, width, height);
  if (!inputs.instances.empty()) instances_.upload(std::span<const gpu::GpuInstance>(inputs.instances));
  cameraBuffer_.upload(std::span<const gpu::GpuCamera>(&inputs.gpuCamera, 1));
  camera_ = inputs.camera;
  setDeformationFrame(scene, t);
}

void GpuScene::setDeformationFrame(const scene::Scene& scene, float t) {
  if (deformation_) {
    deformation_->setTime(scene, DeformedVertices::kFrameSlot, t);
    deformation_->setTime(scene, DeformedVertices::kPreviousSlot, t - 1.0f / scene.settings.fps);
  }
  frameTime_ = t;
  verticesAtFrameTime_ = false;
}

void GpuScene::recordFrameInputs(const FrameInputs& inputs, vk::FrameRecorder& frame) {
  if (!inputs.instances.empty())
    frame.write(kFrameInputs, instances_, std::span<const gpu::GpuInstance>(inputs.instances));
  frame.write(kFrameInputs, cameraBuffer_, std::span<const gpu::GpuCamera>(&inputs.gpuCamera, 1));
  camera_ = inputs.camera;
}

}  // namespace hmb
