#version 450
// An engine's G-buffer (colour, depth, screen velocity, and for the hybrid world normal and
// object id, in its own buffers) packed into the library's image layer and its velocities
// (shared/layer_layout.h), which the post-process and hybrid passes read. Depth
// becomes camera-space depth; a pixel at or past the far plane is background (object 0) at the
// largest depth the gathers know, as the library's own G-buffer writes the background.
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

// Camera-space depth of the engine's value; HMB_MBLUR_MAX_DEPTH where it is the far plane or
// beyond (or not a number), which the gathers treat as the farthest background.
float cameraDepth(float d) {
  float z = d;
  if (params.depthConvention == HMB_ENGINE_DEPTH_STANDARD_Z) {
    // z/w = far (d - near) / (d (far - near))  =>  d = near far / (far - z (far - near))
    z = d < 1.0 ? params.near * params.far / (params.far - d * (params.far - params.near)) : HMB_MBLUR_MAX_DEPTH;
  } else if (params.depthConvention == HMB_ENGINE_DEPTH_REVERSED_Z) {
    // z/w = near (far - d) / (d (far - near))  =>  d = near far / (near + z (far - near)),
    // near / z when far is infinite
    z = d > 0.0 ? (isinf(params.far) ? params.near / d
                                     : params.near * params.far / (params.near + d * (params.far - params.near)))
                : HMB_MBLUR_MAX_DEPTH;
  }
  return (z > 0.0 && z < HMB_MBLUR_MAX_DEPTH) ? z : HMB_MBLUR_MAX_DEPTH;
}

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint i = pixel.y * params.width + pixel.x;
  const float z = cameraDepth(depth[i]);
  const bool background = z >= HMB_MBLUR_MAX_DEPTH;
  const vec2 v = velocity[i];  // the background's too: a turning camera moves the sky
  samples[i] = packLayerSample(color[i].rgb, z, v);
  velocities[i] = layerVelocityEntry(v);  // what tile-max ranks
  // The post-process needs neither normals nor object ids; the hybrid's ray mask, reveal and
  // composite read the engine's.
  if (kEngineSurfaces) surfaces[i] = packLayerSurface(normal[i].xyz, objectId[i], z, v);
  else surfaces[i] = packLayerSurface(vec3(0.0, 0.0, 1.0), background ? 0u : 1u, z, v);
}
