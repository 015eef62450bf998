// The scene on the device: geometry and materials uploaded once, instance transforms and the
// camera of a frame time uploaded per frame. Layouts: kernels/shared/scene_layout.h.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/buffer.h"
#include "hmblur/frame_camera.h"
#include "hmblur/scene.h"
#include "kernels/shared/scene_layout.h"
#include "runtime/vulkan/buffer_group.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb {

class DeformedVertices;

// Every instance's object-to-clip transforms at mid-shutter (t - exposure / 2) and shutter open
// (t - exposure), camera motion included, for the curved path (passes::ShutterPathPass).
std::vector<gpu::GpuShutterClip> shutterClips(const scene::Scene& scene, float t, float exposure, uint32_t width,
                                              uint32_t height);

// Whether anything can move on screen between the previous frame (t - 1/fps) and t: the
// camera, any instance's world transform or any mesh's deformation differs. When nothing does, every screen velocity
// is 0 and the blur passes return the sharp colour.
bool anythingMovesOnScreen(const scene::Scene& scene, float t);
// Whether the camera itself moves between the previous frame and t: then nearly every pixel
// has a screen velocity.
bool cameraMovesOnScreen(const scene::Scene& scene, float t);

class GpuScene {
 public:
  GpuScene(const vk::Context& context, const scene::Scene& scene);
  // A scene over another's vertices, triangles, materials and textures, with frame inputs
  // (instances, camera) of its own: frames in flight of a scene that does not deform (a
  // deforming one is refused, hmb::Error: its vertices are written each frame).
  GpuScene(const vk::Context& context, const GpuScene& sharesDataOf);
  GpuScene(GpuScene&&) noexcept;
  ~GpuScene();

  static constexpr const char* kFrameInputs = "scene-frame-inputs";  // setFrame's writes, recorded

  // Writes instance transforms at t and t - 1/fps and the camera for the frame, and the
  // deformation at both times (recordFrameDeformation applies it).
  void setFrame(const scene::Scene& scene, float t, uint32_t width, uint32_t height);
  // The same transforms and camera, computed on the host, for recordFrameInputs to write when a
  // frame runs (kFrameInputs): nothing staged or waited for, passes recorded after it see
  // them. A deforming scene's deformation at both times is setDeformationFrame's.
  struct FrameInputs {
    std::vector<gpu::GpuInstance> instances;
    gpu::GpuCamera gpuCamera{};
    FrameCamera camera;
  };
  static FrameInputs frameInputs(const scene::Scene& scene, float t, uint32_t width, uint32_t height);
  void recordFrameInputs(const FrameInputs& inputs, vk::FrameRecorder& frame);
  // The deformation at t and t - 1/fps alone, computed on the host for
  // recordFrameDeformation: nothing written until the frame runs.
  void setDeformationFrame(const scene::Scene& scene, float t);

  // Whether the scene has skinned or morphing meshes: their vertices are then deformed on the
  // device (runtime/device_scene/deformed_vertices.h) before anything reads them.
  bool deforms() const { return deformation_ != nullptr; }
  // Records the deformation of the frame set by setFrame: the meshes' vertices at
  // t - 1/fps into previousVertices(), and at t into vertices() unless they already hold it
  // (recordDeformationAt(t), submitted before).
  void recordFrameDeformation(vk::FrameRecorder& frame) const;
  // Records the meshes' vertices deformed at time t into vertices() (for rays traced at t).
  void recordDeformationAt(const scene::Scene& scene, float t, vk::FrameRecorder& frame);

  uint32_t triangleCount() const { return triangleCount_; }
  uint32_t instanceVertexCount() const { return instanceVertexCount_; }
  const FrameCamera& camera() const { return camera_; }
  // Whether the shading kernels run their texture path: when a material samples a texture,
  // or after keepTexturePath(); else they run a build without it (passes::ShadingKernel).
  bool texturePath() const { return texturePath_; }
  void keepTexturePath() { texturePath_ = true; }
  // Whether the tracing kernels walk a top-level tree over the instances: unless the scene has
  // exactly one instance, whose tree rays then enter directly, or after keepTopLevelWalk().
  bool topLevelWalk() const { return topLevelWalk_; }
  void keepTopLevelWalk() { topLevelWalk_ = true; }

  // Per mesh vertex (GpuVertex): deformed ones hold their deformation at the frame time.
  const vk::Buffer& vertices() const { return data_->vertices; }
  // The same at the previous frame (t - 1/fps): vertices() itself when nothing deforms.
  const vk::Buffer& previousVertices() const { return deformation_ ? previousVertices_ : data_->vertices; }
  const vk::Buffer& instanceVertices() const { return data_->instanceVertices; }
  const vk::Buffer& triangles() const { return data_->triangles; }
  const vk::Buffer& instances() const { return instances_; }
  const vk::Buffer& materials() const { return data_->materials; }
  const vk::Buffer& texels() const { return data_->texels; }
  const vk::Buffer& cameraBuffer() const { return cameraBuffer_; }
  // Binds the scene as a shading kernel declares it (kernels/shared/scene_bindings.glsl) from
  // firstBinding on: vertices, instances, materials, texels and camera, or the table of their
  // addresses for a kernel that binds by address.
  void bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const;

 private:
  uint32_t triangleCount_ = 0;
  uint32_t instanceVertexCount_ = 0;
  bool texturePath_ = false;
  bool topLevelWalk_ = true;
  FrameCamera camera_;
  // What frames in flight may share: the scene as uploaded.
  struct Data {
    vk::Buffer vertices;
    vk::Buffer instanceVertices;
    vk::Buffer triangles;
    vk::Buffer materials;
    vk::Buffer texels;
  };
  std::shared_ptr<Data> data_;
  vk::Buffer instances_;
  vk::Buffer cameraBuffer_;
  vk::BufferGroup shading_;  // the buffers above that shading kernels bind together
  std::unique_ptr<DeformedVertices> deformation_;
  vk::Buffer previousVertices_;
  float frameTime_ = 0.0f;
  bool verticesAtFrameTime_ = false;  // recordDeformationAt(frameTime_) was the last to write vertices_
};

}  // namespace hmb
