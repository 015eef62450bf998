#version 450
// The blurred colour into the engine's output image of format rgba32f (write_output_image.glsl).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "engine_layout.h"

#define HMB_OUTPUT_FORMAT rgba32f
#include "write_output_image.glsl"
