// The scene as kernels see it: vertices, triangles, instances, materials and the camera of
// one frame, in buffers laid out identically for GLSL (std430) and C++.
#ifndef HMB_KERNELS_SHARED_SCENE_LAYOUT_H
#define HMB_KERNELS_SHARED_SCENE_LAYOUT_H

#include "glsl_cpp.h"

HMB_GPU_BEGIN

// One vertex of one mesh, in the mesh's own space.
struct GpuVertex {
  vec4 position;  // xyz, w = 1
  vec4 normal;    // xyz, w = 0
  vec2 uv;
  uint pad0;
  uint pad1;
};

// One triangle of one instance: indices into the instance-expanded vertex stream (so the
// transformed positions of this instance are found directly), and the instance.
struct GpuTriangle {
  uint v0;
  uint v1;
  uint v2;
  uint instance;
};

// One vertex of the instance-expanded stream: which mesh vertex, transformed by which instance.
struct GpuInstanceVertex {
  uint meshVertex;
  uint instance;
};

// What shading needs of one instance vertex at the frame time, written by the transform
// kernel so that per-pixel passes read 5 words per vertex instead of mesh vertex, index and
// normal matrix.
struct GpuVertexShading {
  vec4 normal;  // xyz: world-space normal (not normalized), w: unused
  vec2 uv;
  uint pad0;
  uint pad1;
};

#define HMB_INSTANCE_DOUBLE_SIDED 1u

struct GpuInstance {
  mat4 worldCurrent;   // object to world at the frame time t
  mat4 worldPrevious;  // object to world at t - 1/fps
  mat4 normalCurrent;  // inverse transpose of worldCurrent (upper 3x3 used)
  uint objectId;       // 0 is the background
  uint material;
  uint flags;          // HMB_INSTANCE_*
  uint pad0;
};

// Object to clip space at mid-shutter (t - E/2) and shutter open (t - E): with the frame time's
// clip position, three points of each vertex's screen path, for the curved motion path
// (raster/transform_shutter_path.comp). Only frames that use that path upload them.
struct GpuShutterClip {
  mat4 clipMid;
  mat4 clipOpen;
};

#define HMB_NO_TEXTURE 0xffffffffu

// Specialization constant of every shading kernel (shared/shading.glsl): false builds it
// without the texture path, for scenes whose materials have no texture.
#define HMB_SPEC_TEXTURE_PATH 0

struct GpuMaterial {
  vec4 baseColor;      // linear RGBA factor
  uint textureOffset;  // first texel in the texel buffer, HMB_NO_TEXTURE when untextured
  uint textureWidth;
  uint textureHeight;
  uint pad0;
};

struct GpuCamera {
  mat4 viewProjCurrent;   // world to clip at t (Vulkan clip: y down, depth z/w in [0, 1])
  mat4 viewProjPrevious;  // world to clip at t - 1/fps
  mat4 viewCurrent;       // world to camera at t (camera looks down -z)
  vec4 positionCurrent;   // world-space eye at t
  vec4 lightDirection;    // xyz: direction light travels, world space, unit
  vec4 lightColor;        // rgb
  vec4 ambient;           // rgb
  vec4 background;        // rgb: colour where no surface is hit
};

HMB_GPU_END

#ifdef HMB_ADDRESS_TABLES
#ifndef __cplusplus
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer GpuVerticesRef { GpuVertex v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer GpuInstancesRef { GpuInstance v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer GpuMaterialsRef { GpuMaterial v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer GpuTexelsRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer GpuCamerasRef { GpuCamera v[]; };
#endif

HMB_GPU_BEGIN

// The scene's shading buffers by device address, in the order of their bindings
// (shared/scene_bindings.glsl; runtime/device_scene/gpu_scene.h writes it).
struct SceneTable {
  HMB_REFERENCE(GpuVerticesRef) vertices;    // per mesh vertex (normals, uvs)
  HMB_REFERENCE(GpuInstancesRef) instances;  // material, transforms, object id
  HMB_REFERENCE(GpuMaterialsRef) materials;
  HMB_REFERENCE(GpuTexelsRef) texels;        // linear RGBA, two half floats a word: 2 words a texel
  HMB_REFERENCE(GpuCamerasRef) camera;       // one: the frame's camera, light and background
};

HMB_GPU_END

HMB_CHECK_SIZE(SceneTable, 40)
#endif

// The scene takes 5 binding numbers (shared/scene_bindings.glsl); HMB_BIND_BY_ADDRESS builds
// bind one table at the first and leave the others unused, keeping the numbers after it.
#define HMB_SCENE_BINDINGS 5
// Of those, the first four (vertices, instances, materials, texels) are uniform texel buffers
// in the plain build (scene_bindings.glsl); the camera, the last, is a storage buffer.
#define HMB_SCENE_TEXEL_BUFFERS 4
HMB_CHECK_SIZE(GpuVertex, 48)
HMB_CHECK_SIZE(GpuTriangle, 16)
HMB_CHECK_SIZE(GpuInstanceVertex, 8)
HMB_CHECK_SIZE(GpuVertexShading, 32)
HMB_CHECK_SIZE(GpuInstance, 208)
HMB_CHECK_SIZE(GpuShutterClip, 128)
HMB_CHECK_SIZE(GpuMaterial, 32)
HMB_CHECK_SIZE(GpuCamera, 272)

#endif
