#version 450
// Every vertex of the deforming meshes at one time slot, as glTF defines it: the rest position
// and normal plus each morph target's displacement times its weight, then the blend of the
// vertex's joint matrices (the normal through the blend's cofactor matrix, so that shear and
// non-uniform scale keep it perpendicular). Written over the mesh vertex it deforms; the C++
// twin is scene::deformVertex.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "deform_layout.h"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_DEFORM_GROUP) in;

layout(std430, binding = HMB_DEFORM_BINDING_REST) readonly buffer Rest { GpuRestVertex rest[]; };
layout(std430, binding = HMB_DEFORM_BINDING_INFLUENCES) readonly buffer Influences { GpuSkinInfluences influences[]; };
layout(std430, binding = HMB_DEFORM_BINDING_DISPLACEMENTS) readonly buffer Displacements { GpuMorphDisplacement displacements[]; };
layout(std430, binding = HMB_DEFORM_BINDING_DEFORMERS) readonly buffer Deformers { GpuDeformer deformers[]; };
layout(std430, binding = HMB_DEFORM_BINDING_JOINTS) readonly buffer Joints { mat4 joints[]; };
layout(std430, binding = HMB_DEFORM_BINDING_WEIGHTS) readonly buffer Weights { float weights[]; };
layout(std430, binding = HMB_DEFORM_BINDING_OUT) buffer Out { GpuVertex vertices[]; };
layout(push_constant) uniform Params { DeformParams params; };

void main() {
  const uint d = linearInvocationIndex(HMB_DEFORM_GROUP);
  if (d >= params.vertexCount) return;
  const GpuRestVertex r = rest[d];
  const GpuDeformer deformer = deformers[floatBitsToUint(r.normal.w)];
  const uint local = d - deformer.firstVertex;
  vec3 p = r.position.xyz, n = r.normal.xyz;
  for (uint k = 0; k < deformer.targetCount; ++k) {
    const float w = weights[params.weightOffset + deformer.firstWeight + k];
    if (w == 0.0) continue;
    const GpuMorphDisplacement m = displacements[deformer.firstDisplacement + k * deformer.vertexCount + local];
    p += w * m.position.xyz;
    n += w * m.normal.xyz;
  }
  if (deformer.firstJoint != HMB_DEFORM_NO_SKIN) {
    mat4 blend = mat4(0.0);
    for (uint s = 0; s < deformer.influenceSets; ++s) {
      const GpuSkinInfluences set = influences[deformer.firstInfluence + local * deformer.influenceSets + s];
      for (uint i = 0; i < 4; ++i)
        if (set.weights[i] != 0.0) blend += set.weights[i] * joints[params.jointOffset + deformer.firstJoint + set.joints[i]];
    }
    p = (blend * vec4(p, 1.0)).xyz;
    const vec3 a = blend[0].xyz, b = blend[1].xyz, c = blend[2].xyz;
    const mat3 cofactor = mat3(cross(b, c), cross(c, a), cross(a, b));  // det(M) M^-T
    n = (dot(a, cross(b, c)) < 0.0 ? -1.0 : 1.0) * (cofactor * n);
  }
  const float length2 = dot(n, n);
  n = length2 > 0.0 && !isinf(length2) ? n / sqrt(length2) : r.normal.xyz;
  const uint slot = floatBitsToUint(r.position.w);
  vertices[slot].position = vec4(p, 1.0);
  vertices[slot].normal = vec4(n, 0.0);
}
