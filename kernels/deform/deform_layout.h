// Skinned and morphing meshes on the device (deform_vertices.comp): what the host uploads once
// (rest vertices, joint influences, target displacements, one record per deforming instance)
// and per shutter time (joint matrices, morph weights), laid out identically for GLSL (std430)
// and C++ (runtime/device_scene/deformed_vertices.h).
#ifndef HMB_KERNELS_DEFORM_DEFORM_LAYOUT_H
#define HMB_KERNELS_DEFORM_DEFORM_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_DEFORM_GROUP 64

#define HMB_DEFORM_BINDING_REST 0        // GpuRestVertex per deformed vertex
#define HMB_DEFORM_BINDING_INFLUENCES 1  // GpuSkinInfluences per deformed vertex and set of 4
#define HMB_DEFORM_BINDING_DISPLACEMENTS 2  // GpuMorphDisplacement per (target, vertex)
#define HMB_DEFORM_BINDING_DEFORMERS 3   // GpuDeformer per deforming instance
#define HMB_DEFORM_BINDING_JOINTS 4      // mat4 joint matrices of every time slot
#define HMB_DEFORM_BINDING_WEIGHTS 5     // float morph weights of every time slot
#define HMB_DEFORM_BINDING_OUT 6         // GpuVertex per mesh vertex: position and normal written
#define HMB_DEFORM_BINDING_COUNT 7

#define HMB_DEFORM_NO_SKIN 0xffffffffu

HMB_GPU_BEGIN

// A vertex of a deforming mesh before deformation (mesh space).
struct GpuRestVertex {
  vec4 position;  // xyz; w: the bits of the mesh vertex it deforms (its slot in the output)
  vec4 normal;    // xyz; w: the bits of its deformer (GpuDeformer index)
};

// Four joint influences of one vertex: joints index the deformer's joint matrices; weights
// sum to 1 over all of a vertex's sets (the loader normalizes them).
struct GpuSkinInfluences {
  uvec4 joints;
  vec4 weights;
};

// A morph target's displacement of one vertex.
struct GpuMorphDisplacement {
  vec4 position;  // xyz
  vec4 normal;    // xyz
};

// One deforming instance: its vertices (firstVertex.. of the rest vertices), its influences
// (influenceSets of 4 per vertex from firstInfluence, vertex-major), its targets' displacements
// (target-major from firstDisplacement), and where its joint matrices and weights start in a
// time slot.
struct GpuDeformer {
  uint firstVertex;
  uint vertexCount;
  uint influenceSets;      // 0 (no skin), 1 or 2
  uint firstInfluence;
  uint targetCount;
  uint firstDisplacement;
  uint firstJoint;         // HMB_DEFORM_NO_SKIN without a skin
  uint firstWeight;
};

// Push constants: which time slot's joint matrices and weights to deform with.
struct DeformParams {
  uint vertexCount;   // deformed vertices (all deformers')
  uint jointOffset;   // the slot's first joint matrix
  uint weightOffset;  // the slot's first weight
  uint pad0;
};

HMB_GPU_END

HMB_CHECK_SIZE(GpuRestVertex, 32)
HMB_CHECK_SIZE(GpuSkinInfluences, 32)
HMB_CHECK_SIZE(GpuMorphDisplacement, 32)
HMB_CHECK_SIZE(GpuDeformer, 32)
HMB_CHECK_SIZE(DeformParams, 16)

#endif
