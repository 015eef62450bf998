// Layout of the engine backend's kernels (include/hmblur/engine_motion_blur.h): an engine's own
// G-buffer, in the formats the public header documents, read into the library's packed layer.
#ifndef HMB_KERNELS_ENGINE_ENGINE_LAYOUT_H
#define HMB_KERNELS_ENGINE_ENGINE_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_ENGINE_GROUP_X 8
#define HMB_ENGINE_GROUP_Y 8

// pack_engine_gbuffer (the engine's buffers) and pack_engine_images (its images, read with
// texelFetch: colour and velocity any float format, depth a depth view, normal any float
// format, object id an unsigned-integer format)
#define HMB_ENGINE_BINDING_COLOR 0     // vec4 per pixel: linear RGB (alpha ignored)
#define HMB_ENGINE_BINDING_DEPTH 1     // float per pixel: params.depthConvention
#define HMB_ENGINE_BINDING_VELOCITY 2  // vec2 per pixel: pixels per frame, current - previous, y down
#define HMB_ENGINE_BINDING_SAMPLES 3   // the packed layer's samples (uvec4), written
#define HMB_ENGINE_BINDING_SURFACES 4  // the packed layer's surfaces (uvec4), written
#define HMB_ENGINE_BINDING_NORMAL 5     // vec4 per pixel: world normal (xyz); read with HMB_SPEC_ENGINE_SURFACES
#define HMB_ENGINE_BINDING_OBJECT_ID 6  // uint per pixel: object id (0: background); likewise
#define HMB_ENGINE_BINDING_VELOCITIES 7  // the G-buffer's velocities (vec2 per pixel: shared/layer_layout.h), written
#define HMB_ENGINE_BINDING_COUNT 8
#define HMB_ENGINE_COLOUR_IMAGES_BINDING_COUNT 6  // pack_engine_colour_images: no normal or object id
// Specialization constant: true when the engine gives normals and object ids (the hybrid
// needs them), false for +z and 1 (0 where background). A constant, not a parameter: on CPU
// devices both sides of a branch run under a mask, so the build without them reads nothing.
#define HMB_SPEC_ENGINE_SURFACES 0

// write_output_rgba16f / write_output_rgba32f: the blurred colour into the engine's image.
#define HMB_ENGINE_OUTPUT_BINDING_COLOR 0  // vec4 per pixel, read
#define HMB_ENGINE_OUTPUT_BINDING_IMAGE 1  // the engine's storage image, written (alpha 1)
#define HMB_ENGINE_OUTPUT_BINDING_COUNT 2

// What the engine's velocity values are (EngineImages on the host).
#define HMB_ENGINE_VELOCITY_PIXELS 0  // pixels per frame, +y down
#define HMB_ENGINE_VELOCITY_NDC 1     // Vulkan NDC per frame ([-1, 1] across the image, +y down)
// How the engine's normals are stored.
#define HMB_ENGINE_NORMAL_XYZ 0               // xyz as they are (a float format)
#define HMB_ENGINE_NORMAL_XYZ_UNORM 1         // xyz * 0.5 + 0.5 (RGB10A2 and other UNORM formats)
#define HMB_ENGINE_NORMAL_OCTAHEDRAL 2        // octahedral in [-1, 1]^2 (RG16_SNORM, RG16F)
#define HMB_ENGINE_NORMAL_OCTAHEDRAL_UNORM 3  // octahedral * 0.5 + 0.5 (RG16_UNORM)

// What the engine's depth values are (EngineDepth on the host).
#define HMB_ENGINE_DEPTH_VIEW 0         // camera-space depth: distance along the view axis, > 0
#define HMB_ENGINE_DEPTH_STANDARD_Z 1   // z/w in [0, 1], 0 at near, 1 at far (perspective)
#define HMB_ENGINE_DEPTH_REVERSED_Z 2   // z/w in [0, 1], 1 at near, 0 at far (far may be infinite)

HMB_GPU_BEGIN
struct EngineGBufferParams {
  uint width;
  uint height;
  uint depthConvention;  // HMB_ENGINE_DEPTH_*
  uint velocityUnits;    // HMB_ENGINE_VELOCITY_*
  float near;            // the projection's near plane (z/w conventions only)
  float far;             // its far plane; infinity for an infinite reversed-z projection
  uint normalEncoding;   // HMB_ENGINE_NORMAL_*
  uint pad0;
};

struct EngineOutputParams {
  uint width;
  uint height;
  uint pad0;
  uint pad1;
};
HMB_GPU_END
HMB_CHECK_SIZE(EngineGBufferParams, 32)
HMB_CHECK_SIZE(EngineOutputParams, 16)

#endif
