#version 450
// An engine's G-buffer (colour, depth, screen velocity, and for the hybrid world normal and
// object id, in its own buffers) packed into the library's image layer and its velocities
// (shared/layer_layout.h), which the post-process and hybrid passes read (engine_pixel.glsl).
// Depth becomes camera-space depth; a pixel at or past the far plane is background (object 0)
// at the largest depth the gathers know, as the library's own G-buffer writes the background.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "engine_layout.h"
#include "../shared/layer_layout.h"
#include "../mblur/mblur_layout.h"

layout(local_size_x = HMB_ENGINE_GROUP_X, local_size_y = HMB_ENGINE_GROUP_Y) in;
layout(constant_id = HMB_SPEC_ENGINE_SURFACES) const bool kEngineSurfaces = true;

layout(std430, binding = HMB_ENGINE_BINDING_COLOR) readonly buffer Color { vec4 color[]; };
layout(std430, binding = HMB_ENGINE_BINDING_DEPTH) readonly buffer Depth { float depth[]; };
layout(std430, binding = HMB_ENGINE_BINDING_VELOCITY) readonly buffer Velocity { vec2 velocity[]; };
layout(std430, binding = HMB_ENGINE_BINDING_SAMPLES) writeonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = HMB_ENGINE_BINDING_SURFACES) writeonly buffer Surfaces { uvec4 surfaces[]; };
layout(std430, binding = HMB_ENGINE_BINDING_NORMAL) readonly buffer Normal { vec4 normal[]; };
layout(std430, binding = HMB_ENGINE_BINDING_OBJECT_ID) readonly buffer ObjectId { uint objectId[]; };
layout(std430, binding = HMB_ENGINE_BINDING_VELOCITIES) writeonly buffer Velocities { vec2 velocities[]; };
layout(push_constant) uniform Params { EngineGBufferParams params; };

#include "engine_pixel.glsl"

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint i = pixel.y * params.width + pixel.x;
  packEnginePixel(i, color[i].rgb, depth[i], velocity[i], kEngineSurfaces ? normal[i].xyz : vec3(0.0),
                  kEngineSurfaces ? objectId[i] : 0u, kEngineSurfaces);
}
