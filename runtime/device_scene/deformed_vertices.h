// The deforming meshes of a scene on the device (kernels/deform/): their rest vertices, joint
// influences and target displacements uploaded once; per time slot, the joint matrices and
// morph weights at that slot's time. record() deforms the meshes' vertices at one slot into a
// vertex buffer laid out as the scene's (gpu::GpuVertex): the scene's own for the frame time,
// or a copy for the previous frame.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/buffer.h"
#include "hmblur/scene.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
}

namespace hmb {

class FramePlan;

// Why the deformation's passes are skipped in a scene without deforming meshes.
inline constexpr const char* kNoDeformationReason = "no skinned or morphing mesh in the scene";

// Enters DeformedVertices::kName in the plan: run when the scene has deforming meshes, else
// skipped with kNoDeformationReason.
void planDeformation(FramePlan& plan, const scene::Scene& scene);

class DeformedVertices {
 public:
  static constexpr const char* kName = "deform-vertices";
  // Time slots: the frame time, the previous frame, and any other time (a ray's).
  static constexpr uint32_t kFrameSlot = 0, kPreviousSlot = 1, kAnyTimeSlot = 2, kSlots = 3;

  // meshVertexBase: each mesh's first vertex in the scene's vertex buffer. Throws hmb::Error
  // for a scene the loader would not make: a deforming mesh shared with another instance, a
  // joint index past its skin, more than 2^31 of anything.
  DeformedVertices(const vk::Context& context, const scene::Scene& scene, std::span<const uint32_t> meshVertexBase);

  uint32_t vertexCount() const { return vertexCount_; }
  // The joint matrices and weights of slot `slot` at time t, computed on the host; record()
  // carries them to the device in the command buffer, so nothing is staged or waited for.
  void setTime(const scene::Scene& scene, uint32_t slot, float t);
  // Writes the slot's joint matrices and weights, then every deformed vertex's position and
  // normal at the slot's time into `vertices`.
  void record(vk::FrameRecorder& frame, uint32_t slot, const vk::Buffer& vertices) const;

 private:
  const vk::Context& context_;
  vk::ComputeKernel kernel_;
  uint32_t vertexCount_ = 0;
  uint32_t jointsPerSlot_ = 0;
  uint32_t weightsPerSlot_ = 0;
  std::vector<uint32_t> deformingInstances_;  // scene instance of each deformer
  std::vector<uint32_t> paletteSkins_;        // per skin in the joint matrices, an instance it deforms
  std::vector<glm::mat4> slotJoints_[kSlots];  // setTime's, written by record()
  std::vector<float> slotWeights_[kSlots];
  vk::Buffer rest_, influences_, displacements_, deformers_, joints_, weights_;
};

}  // namespace hmb
