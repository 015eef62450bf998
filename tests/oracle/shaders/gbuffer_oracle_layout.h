// Bindings of the G-buffer oracle's shaders (tests/oracle/graphics_gbuffer.h), one descriptor set.
#ifndef HMB_TESTS_ORACLE_GBUFFER_ORACLE_LAYOUT_H
#define HMB_TESTS_ORACLE_GBUFFER_ORACLE_LAYOUT_H

#include "kernels/shared/glsl_cpp.h"

#define HMB_GBUFFER_ORACLE_BINDING_TRIANGLES 0      // GpuTriangle per scene triangle
#define HMB_GBUFFER_ORACLE_BINDING_CLIP_CURRENT 1   // vec4 per instance vertex, at t
#define HMB_GBUFFER_ORACLE_BINDING_CLIP_PREVIOUS 2  // vec4 per instance vertex, at t - 1/fps
#define HMB_GBUFFER_ORACLE_BINDING_SHADING 3        // GpuVertexShading per instance vertex
#define HMB_GBUFFER_ORACLE_BINDING_SCENE 4          // the scene's 5 shading buffers (scene_bindings.glsl)
#define HMB_GBUFFER_ORACLE_BINDING_COUNT 9

HMB_GPU_BEGIN
struct GBufferOracleParams {
  uint width;
  uint height;
  uint pad0;
  uint pad1;
};
HMB_GPU_END
HMB_CHECK_SIZE(GBufferOracleParams, 16)

#endif
