#version 450
// An engine's G-buffer images packed into the library's layer with its normal and object-id
// images: the hybrid's, and the post-process's where given (pack_engine_images.glsl).
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_samplerless_texture_functions : require
#include "../shared/float_controls.glsl"
#include "engine_layout.h"
#include "../shared/layer_layout.h"
#include "../mblur/mblur_layout.h"

#define HMB_ENGINE_IMAGE_SURFACES 1
#include "pack_engine_images.glsl"
