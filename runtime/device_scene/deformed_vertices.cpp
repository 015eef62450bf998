#include "runtime/device_scene/deformed_vertices.h"

#include <algorithm>
#include <bit>
#include <map>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/deform/deform_layout.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"
#include "scenes/deformation.h"

namespace hmb {

void planDeformation(FramePlan& plan, const scene::Scene& scene) {
  if (scene.hasDeformation())
    plan.run(DeformedVertices::kName);
  else
    plan.skip(DeformedVertices::kName, kNoDeformationReason);
}

DeformedVertices::DeformedVertices(const vk::Context& context, const scene::Scene& scene,
                                   std::span<const uint32_t> meshVertexBase)
    : context_(context), kernel_(context, kernels::kernel("deform/deform_vertices")) {
  std::vector<gpu::GpuRestVertex> rest;
  std::vector<gpu::GpuSkinInfluences> influences;
  std::vector<gpu::GpuMorphDisplacement> displacements;
  std::vector<gpu::GpuDeformer> deformers;
  uint64_t jointCount = 0, weightCount = 0;  // per time slot
  std::map<int32_t, uint32_t> skinFirstJoint;  // one set of joint matrices per skin, shared by its meshes
  std::vector<uint32_t> meshUses(scene.meshes.size(), 0);
  for (const scene::Instance& instance : scene.instances) ++meshUses.at(instance.mesh);
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& instance = scene.instances[i];
    if (!instance.deforms()) continue;
    const scene::Mesh& mesh = scene.meshes.at(instance.mesh);
    if (meshUses[instance.mesh] > 1)
      throw Error("deform-vertices: mesh '" + mesh.name + "' deforms in one instance and is drawn by another");
    if (instance.skin >= 0)
      for (const uint32_t joint : mesh.joints)
        if (joint >= scene.skins.at(size_t(instance.skin)).joints.size())
          throw Error("deform-vertices: mesh '" + mesh.name + "' names joint " + std::to_string(joint) +
                      ", past its skin's");
    const auto vertices = static_cast<uint32_t>(mesh.positions.size());
    gpu::GpuDeformer d{};
    d.firstVertex = static_cast<uint32_t>(rest.size());
    d.vertexCount = vertices;
    d.influenceSets = instance.skin >= 0 ? mesh.influences / 4 : 0u;
    d.firstInfluence = static_cast<uint32_t>(influences.size());
    d.targetCount = instance.morphNode >= 0 ? static_cast<uint32_t>(mesh.targets.size()) : 0u;
    d.firstDisplacement = static_cast<uint32_t>(displacements.size());
    d.firstJoint = HMB_DEFORM_NO_SKIN;
    if (instance.skin >= 0) {
      const auto [at, added] = skinFirstJoint.try_emplace(instance.skin, static_cast<uint32_t>(jointCount));
      if (added) {
        jointCount += scene.skins.at(size_t(instance.skin)).joints.size();
        paletteSkins_.push_back(i);
      }
      d.firstJoint = at->second;
    }
    d.firstWeight = static_cast<uint32_t>(weightCount);
    const auto deformer = static_cast<uint32_t>(deformers.size());
    for (uint32_t v = 0; v < vertices; ++v) {
      const glm::vec3 normal = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f, 0.0f, 1.0f);
      rest.push_back({glm::vec4(mesh.positions[v], std::bit_cast<float>(meshVertexBase[instance.mesh] + v)),
                      glm::vec4(normal, std::bit_cast<float>(deformer))});
      for (uint32_t s = 0; s < d.influenceSets; ++s) {
        gpu::GpuSkinInfluences set{};
        for (uint32_t c = 0; c < 4; ++c) {
          set.joints[int(c)] = mesh.joints[size_t(v) * mesh.influences + 4 * s + c];
          set.weights[int(c)] = mesh.weights[size_t(v) * mesh.influences + 4 * s + c];
        }
        influences.push_back(set);
      }
    }
    for (uint32_t k = 0; k < d.targetCount; ++k) {
      const scene::MorphTarget& target = mesh.targets[k];
      for (uint32_t v = 0; v < vertices; ++v)
        displacements.push_back({glm::vec4(v < target.positions.size() ? target.positions[v] : glm::vec3(0.0f), 0.0f),
                                 glm::vec4(v < target.normals.size() ? target.normals[v] : glm::vec3(0.0f), 0.0f)});
    }
    weightCount += d.targetCount;
    deformers.push_back(d);
    deformingInstances_.push_back(i);
  }
  for (const uint64_t count : {uint64_t(rest.size()), uint64_t(influences.size()), uint64_t(displacements.size()),
                               jointCount * kSlots, weightCount * kSlots})
    if (count >= 0x7fffffffu) throw Error("the scene deforms more than one frame can address");
  jointsPerSlot_ = static_cast<uint32_t>(jointCount);
  weightsPerSlot_ = static_cast<uint32_t>(weightCount);
  vertexCount_ = static_cast<uint32_t>(rest.size());
  // Every buffer holds at least one element: a kernel binds them all.
  if (influences.empty()) influences.emplace_back();
  if (displacements.empty()) displacements.emplace_back();
  if (rest.empty()) rest.emplace_back();
  if (deformers.empty()) deformers.emplace_back();
  rest_ = vk::uploadedBuffer(context, rest, "deform rest vertices");
  influences_ = vk::uploadedBuffer(context, influences, "deform joint influences");
  displacements_ = vk::uploadedBuffer(context, displacements, "deform target displacements");
  deformers_ = vk::uploadedBuffer(context, deformers, "deformers");
  joints_ = vk::Buffer(context, std::max(1u, kSlots * jointsPerSlot_) * sizeof(glm::mat4), vk::MemoryUse::Device,
                       "deform joint matrices");
  weights_ = vk::Buffer(context, std::max(1u, kSlots * weightsPerSlot_) * sizeof(float), vk::MemoryUse::Device,
                        "deform morph weights");
}

void DeformedVertices::setTime(const scene::Scene& scene, uint32_t slot, float t) {
  if (slot >= kSlots) throw Error("deform-vertices: no time slot " + std::to_string(slot));
  std::vector<glm::mat4> joints;
  std::vector<float> weights;
  for (const uint32_t i : paletteSkins_) {
    const std::vector<glm::mat4> matrices = scene::jointMatricesAt(scene, scene.instances.at(i), t);
    joints.insert(joints.end(), matrices.begin(), matrices.end());
  }
  for (const uint32_t i : deformingInstances_) {
    const std::vector<float> w = scene::morphWeightsAt(scene, scene.instances.at(i), t);
    weights.insert(weights.end(), w.begin(), w.end());
  }
  if (joints.size() != jointsPerSlot_ || weights.size() != weightsPerSlot_)
    throw Error("deform-vertices: the scene's skins or targets changed since its upload");
  slotJoints_[slot] = std::move(joints);
  slotWeights_[slot] = std::move(weights);
}

void DeformedVertices::record(vk::FrameRecorder& frame, uint32_t slot, const vk::Buffer& vertices) const {
  if (slot >= kSlots) throw Error("deform-vertices: no time slot " + std::to_string(slot));
  if (slotJoints_[slot].size() != jointsPerSlot_ || slotWeights_[slot].size() != weightsPerSlot_)
    throw Error("deform-vertices: record() of a time slot setTime() did not set");
  if (jointsPerSlot_ > 0)
    frame.write(kName, joints_, std::as_bytes(std::span<const glm::mat4>(slotJoints_[slot])),
                VkDeviceSize(slot) * jointsPerSlot_ * sizeof(glm::mat4));
  if (weightsPerSlot_ > 0)
    frame.write(kName, weights_, std::as_bytes(std::span<const float>(slotWeights_[slot])),
                VkDeviceSize(slot) * weightsPerSlot_ * sizeof(float));
  const gpu::DeformParams params{vertexCount_, slot * jointsPerSlot_, slot * weightsPerSlot_, 0u};
  frame.dispatch(kName, kernel_,
                 {{HMB_DEFORM_BINDING_REST, &rest_},
                  {HMB_DEFORM_BINDING_INFLUENCES, &influences_},
                  {HMB_DEFORM_BINDING_DISPLACEMENTS, &displacements_},
                  {HMB_DEFORM_BINDING_DEFORMERS, &deformers_},
                  {HMB_DEFORM_BINDING_JOINTS, &joints_},
                  {HMB_DEFORM_BINDING_WEIGHTS, &weights_},
                  {HMB_DEFORM_BINDING_OUT, &vertices}},
                 params, vk::foldedGroups(vk::groupsFor(vertexCount_, HMB_DEFORM_GROUP)));
}

}  // namespace hmb
