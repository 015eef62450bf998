// The scene's shading buffers as a kernel binds them, from its binding HMB_SCENE_BINDING on
// (defined by the including kernel): vertices, instances, materials, texels and camera, or in
// builds with HMB_BIND_BY_ADDRESS one SceneTable of their addresses. Either way the kernels
// (and shared/shading.glsl) read the same names: vertices[i], sceneInstances[i], camera, ...,
// and textureTexel(i) for texel i of the textures (linear RGBA).
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
vec4 textureTexel(uint i) {
  return vec4(unpackHalf2x16(texels[2u * i]), unpackHalf2x16(texels[2u * i + 1u]));
}
#else
// The textures' texels are read at per-pixel addresses through a uniform texel buffer (two
// linear half-float RGBA texels a record; see trace/trace_scene_bindings.glsl for why).
#extension GL_EXT_samplerless_texture_functions : require
layout(std430, binding = HMB_SCENE_BINDING + 0) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_SCENE_BINDING + 1) readonly buffer SceneInstances { GpuInstance sceneInstances[]; };
layout(std430, binding = HMB_SCENE_BINDING + 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(binding = HMB_SCENE_BINDING + 3) uniform utextureBuffer textureTexels2;
layout(std430, binding = HMB_SCENE_BINDING + 4) readonly buffer Camera { GpuCamera camera; };
vec4 textureTexel(uint i) {
  const uvec4 two = texelFetch(textureTexels2, int(i >> 1u));
  const uvec2 texel = (i & 1u) == 0u ? two.xy : two.zw;
  return vec4(unpackHalf2x16(texel.x), unpackHalf2x16(texel.y));
}
#endif

#endif
