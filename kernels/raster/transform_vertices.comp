#version 450
// Clip-space position of every instance vertex at the frame time and at the previous frame,
// and what shading needs of it (world normal, uv). A deformed vertex has a position of its own
// at each of the two times (kernels/deform/), so its screen velocity is exact.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "raster_layout.h"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;
layout(constant_id = HMB_SPEC_TRANSFORM_DEFORMED) const bool kDeformed = false;

layout(std430, binding = HMB_TRANSFORM_BINDING_VERTICES) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_TRANSFORM_BINDING_INSTANCE_VERTICES) readonly buffer InstanceVertices { GpuInstanceVertex instanceVertices[]; };
layout(std430, binding = HMB_TRANSFORM_BINDING_INSTANCES) readonly buffer Instances { GpuInstance instances[]; };
layout(std430, binding = HMB_TRANSFORM_BINDING_CAMERA) readonly buffer Camera { GpuCamera camera; };
layout(std430, binding = HMB_TRANSFORM_BINDING_CLIP_CURRENT) writeonly buffer ClipCurrent { vec4 clipCurrent[]; };
layout(std430, binding = HMB_TRANSFORM_BINDING_CLIP_PREVIOUS) writeonly buffer ClipPrevious { vec4 clipPrevious[]; };
layout(std430, binding = HMB_TRANSFORM_BINDING_SHADING) writeonly buffer Shading { GpuVertexShading shading[]; };
layout(std430, binding = HMB_TRANSFORM_BINDING_PREVIOUS_VERTICES) readonly buffer PreviousVertices { GpuVertex previousVertices[]; };
layout(push_constant) uniform Params { uint vertexCount; };

void main() {
  const uint i = linearInvocationIndex(HMB_RASTER_GROUP);
  if (i >= vertexCount) return;
  const GpuInstanceVertex iv = instanceVertices[i];
  const vec4 p = vertices[iv.meshVertex].position;
  clipCurrent[i] = camera.viewProjCurrent * (instances[iv.instance].worldCurrent * p);
  const vec4 previous = kDeformed ? previousVertices[iv.meshVertex].position : p;
  clipPrevious[i] = camera.viewProjPrevious * (instances[iv.instance].worldPrevious * previous);
  shading[i].normal = vec4(mat3(instances[iv.instance].normalCurrent) * vertices[iv.meshVertex].normal.xyz, 0.0);
  shading[i].uv = vertices[iv.meshVertex].uv;
}
