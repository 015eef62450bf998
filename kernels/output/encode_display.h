// Layout of output/encode_display.comp: linear RGBA float image (or an image layer's packed
// samples) -> display RGBA8.
#ifndef HMB_KERNELS_OUTPUT_ENCODE_DISPLAY_H
#define HMB_KERNELS_OUTPUT_ENCODE_DISPLAY_H

#include "../shared/glsl_cpp.h"

#define HMB_ENCODE_DISPLAY_GROUP_X 8
#define HMB_ENCODE_DISPLAY_GROUP_Y 8

// The input, 16 bytes per pixel, row-major, top row first: vec4 linear RGBA, or with
// HMB_SPEC_ENCODE_LAYER_SAMPLES a layer's samples (shared/layer_layout.h: the sharp frame is the
// G-buffer's colour, displayed without a copy).
#define HMB_ENCODE_DISPLAY_BINDING_LINEAR 0
#define HMB_SPEC_ENCODE_LAYER_SAMPLES 0  // bool: the input is a layer's samples
#define HMB_ENCODE_DISPLAY_BINDING_RGBA8 1   // uint per pixel: R in the low byte, A in the high
#define HMB_ENCODE_DISPLAY_BINDING_COUNT 2

HMB_GPU_BEGIN
struct EncodeDisplayParams {
  uint width;
  uint height;
  uint pad0;
  uint pad1;
};
HMB_GPU_END
HMB_CHECK_SIZE(EncodeDisplayParams, 16)

#endif
