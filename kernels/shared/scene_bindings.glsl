// The scene's shading buffers as a kernel binds them, from its binding HMB_SCENE_BINDING on
// (defined by the including kernel): vertices, instances, materials, texels and camera, or in
// builds with HMB_BIND_BY_ADDRESS one SceneTable of their addresses. Either way the kernels
// (and shared/shading.glsl) read the same names: vertices[i], sceneInstances[i], camera, ...
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
#else
layout(std430, binding = HMB_SCENE_BINDING + 0) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_SCENE_BINDING + 1) readonly buffer SceneInstances { GpuInstance sceneInstances[]; };
layout(std430, binding = HMB_SCENE_BINDING + 2) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = HMB_SCENE_BINDING + 3) readonly buffer Texels { uint texels[]; };
layout(std430, binding = HMB_SCENE_BINDING + 4) readonly buffer Camera { GpuCamera camera; };
#endif

#endif
