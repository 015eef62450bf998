// The scene's shading buffers as a kernel binds them, from its binding HMB_SCENE_BINDING on
// (defined by the including kernel): vertices, instances, materials, texels and camera, or in
// builds with HMB_BIND_BY_ADDRESS one SceneTable of their addresses. Either way the kernels
// (and shared/shading.glsl) read the same names: vertices[i], sceneInstances[i], camera, ...,
// and textureTexel(i) for texel i of the textures.
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
uint textureTexel(uint i) { return texels[i]; }
#else
// The textures' texels are read at per-pixel addresses through a uniform texel buffer (four
// RGBA8 texels a record; see trace/trace_scene_bindings.glsl for why).
#extension GL_EXT_samplerless_texture_functions : require
layout(std430, binding = HMB_SCENE_BINDING + 0) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_SCENE_BINDING + 1) readonly buffer SceneInstances { GpuInstance sceneInstances[]; };
layout(std430, binding = HMB_SCENE_BINDING + 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(binding = HMB_SCENE_BINDING + 3) uniform utextureBuffer textureTexels4;
layout(std430, binding = HMB_SCENE_BINDING + 4) readonly buffer Camera { GpuCamera camera; };
uint textureTexel(uint i) {
  const uvec4 four = texelFetch(textureTexels4, int(i >> 2u));
  const uint lane = i & 3u;
  return lane == 0u ? four.x : lane == 1u ? four.y : lane == 2u ? four.z : four.w;
}
#endif

#endif
