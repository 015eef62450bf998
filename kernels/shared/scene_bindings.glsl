// The scene's shading buffers as a kernel binds them, from its binding HMB_SCENE_BINDING on
// (defined by the including kernel): vertices, instances, materials, texels and camera, or in
// builds with HMB_BIND_BY_ADDRESS one SceneTable of their addresses. Either way the kernels
// (and shared/shading.glsl) read them through the functions below (vertexNormal(i),
// instanceMaterial(i), textureTexel(i), ...) and `camera`. In the plain build the four arrays
// read at per-pixel addresses are uniform texel buffers of 16-byte records
// (texel_records.glsl): a GpuVertex is 3 records, a GpuInstance 13, a GpuMaterial 2, and a
// record holds two texels (linear RGBA, half floats).
#ifndef HMB_KERNELS_SHARED_SCENE_BINDINGS_GLSL
#define HMB_KERNELS_SHARED_SCENE_BINDINGS_GLSL

#include "scene_layout.h"

#ifdef HMB_BIND_BY_ADDRESS
layout(std430, binding = HMB_SCENE_BINDING) readonly buffer Scene { SceneTable sceneTable; };
#define vertices sceneTable.vertices.v
#define sceneInstances sceneTable.instances.v
#define materials sceneTable.materials.v
#define texels sceneTable.texels.v
#define camera sceneTable.camera.v[0]
vec3 vertexNormal(uint i) { return vertices[i].normal.xyz; }
vec2 vertexUv(uint i) { return vertices[i].uv; }
uint instanceObjectId(uint i) { return sceneInstances[i].objectId; }
uint instanceMaterial(uint i) { return sceneInstances[i].material; }
mat4 instanceWorldPrevious(uint i) { return sceneInstances[i].worldPrevious; }
vec4 materialBaseColor(uint m) { return materials[m].baseColor; }
uvec3 materialTexture(uint m) {  // first texel (HMB_NO_TEXTURE: none), width, height
  return uvec3(materials[m].textureOffset, materials[m].textureWidth, materials[m].textureHeight);
}
vec4 textureTexel(uint i) {
  return vec4(unpackHalf2x16(texels[2u * i]), unpackHalf2x16(texels[2u * i + 1u]));
}
#else
#include "texel_records.glsl"
layout(binding = HMB_SCENE_BINDING + 0) uniform utextureBuffer vertexTexels;
layout(binding = HMB_SCENE_BINDING + 1) uniform utextureBuffer instanceTexels;
layout(binding = HMB_SCENE_BINDING + 2) uniform utextureBuffer materialTexels;
layout(binding = HMB_SCENE_BINDING + 3) uniform utextureBuffer textureTexels2;
layout(std430, binding = HMB_SCENE_BINDING + 4) readonly buffer Camera { GpuCamera camera; };
vec3 vertexNormal(uint i) { return floatRecordAt(vertexTexels, 3u * i + 1u).xyz; }
vec2 vertexUv(uint i) { return floatRecordAt(vertexTexels, 3u * i + 2u).xy; }
// Record 12 of an instance: objectId, material, flags.
uint instanceObjectId(uint i) { return recordAt(instanceTexels, 13u * i + 12u).x; }
uint instanceMaterial(uint i) { return recordAt(instanceTexels, 13u * i + 12u).y; }
mat4 instanceWorldPrevious(uint i) { return mat4RecordsAt(instanceTexels, 13u * i + 4u); }  // records 4-7
vec4 materialBaseColor(uint m) { return floatRecordAt(materialTexels, 2u * m); }
uvec3 materialTexture(uint m) { return recordAt(materialTexels, 2u * m + 1u).xyz; }
vec4 textureTexel(uint i) {
  const uvec2 texel = halfRecordAt(textureTexels2, i);
  return vec4(unpackHalf2x16(texel.x), unpackHalf2x16(texel.y));
}
#endif

#endif
