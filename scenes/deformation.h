// glTF deformation on the host (glTF 2.0, sections 3.7.2.2 and 3.8): morph targets first, then
// the skin. The reference the deform kernel (kernels/deform/) is tested against, and what
// bounds and "does anything move" questions are answered with.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/scene.h"

namespace hmb::scene {

// The instance's morph weights at time t, one per target of its mesh: its node's rest weights
// with the node's weight channels sampled at t. Empty for an instance without targets.
std::vector<float> morphWeightsAt(const Scene& scene, const Instance& instance, float t);

// The skin's joint matrices at time t, one per joint: the joint's world matrix times its
// inverse bind matrix. Empty for an instance without a skin.
std::vector<glm::mat4> jointMatricesAt(const Scene& scene, const Instance& instance, float t);

struct DeformedVertex {
  glm::vec3 position;
  glm::vec3 normal;  // unit; the rest normal where the deformed one vanishes
};

// One vertex: its rest position and normal plus the weighted target displacements, then the
// blend of its joints' matrices (the normal through the blend's cofactor matrix, so that shear
// and non-uniform scale keep it perpendicular to the surface).
DeformedVertex deformVertex(const Mesh& mesh, uint32_t vertex, std::span<const float> morphWeights,
                            std::span<const glm::mat4> jointMatrices);

struct DeformedMesh {
  std::vector<glm::vec3> positions;  // in the instance's node space (world for a skinned mesh)
  std::vector<glm::vec3> normals;
};

// The instance's mesh deformed at time t (its rest vertices when it does not deform).
DeformedMesh deformedMeshAt(const Scene& scene, const Instance& instance, float t);

// The bounds of the instance's mesh deformed at time t, in its node's space.
Aabb deformedBoundsAt(const Scene& scene, const Instance& instance, float t);

// Whether any animation channel drives the instance's deformation: one of its skin's joints
// (or their ancestors) is animated, or its morph node's weights are.
bool deformationIsAnimated(const Scene& scene, const Instance& instance);

// Whether the instance's deformation differs between the two times (its weights or joint
// matrices do).
bool deformationDiffers(const Scene& scene, const Instance& instance, float t0, float t1);

}  // namespace hmb::scene
