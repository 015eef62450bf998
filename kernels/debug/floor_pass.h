// Layout of debug/floor_pass.comp: the floor that every per-pixel pass is measured against in
// the benchmarks: one 16-byte word read and one written per pixel, the least any full-screen
// pass does.
#ifndef HMB_KERNELS_DEBUG_FLOOR_PASS_H
#define HMB_KERNELS_DEBUG_FLOOR_PASS_H

#include "../shared/glsl_cpp.h"

#define HMB_FLOOR_GROUP_X 8
#define HMB_FLOOR_GROUP_Y 8

#define HMB_FLOOR_BINDING_INPUT 0   // uvec4 per pixel
#define HMB_FLOOR_BINDING_OUTPUT 1  // uvec4 per pixel, written
#define HMB_FLOOR_BINDING_COUNT 2

HMB_GPU_BEGIN
struct FloorParams {
  uint width;
  uint height;
  uint pad0;
  uint pad1;
};
HMB_GPU_END
HMB_CHECK_SIZE(FloorParams, 16)

#endif
