// Layout of debug/test_pattern.comp: a known image that proves dispatch, buffers and
// timestamps end to end, independent of any scene.
#ifndef HMB_KERNELS_DEBUG_TEST_PATTERN_H
#define HMB_KERNELS_DEBUG_TEST_PATTERN_H

#include "../shared/glsl_cpp.h"

#define HMB_TEST_PATTERN_GROUP_X 8
#define HMB_TEST_PATTERN_GROUP_Y 8

#define HMB_TEST_PATTERN_BINDING_LINEAR 0  // vec4 per pixel, written
#define HMB_TEST_PATTERN_BINDING_COUNT 1

// Checker squares of this many pixels.
#define HMB_TEST_PATTERN_CHECKER 16u

HMB_GPU_BEGIN
struct TestPatternParams {
  uint width;
  uint height;
  float time;  // moves a disc across the image: x = fract(time) of the width
  uint pad0;
};
HMB_GPU_END
HMB_CHECK_SIZE(TestPatternParams, 16)

#endif
