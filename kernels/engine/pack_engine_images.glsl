// An engine's G-buffer in its own images (colour, depth, screen velocity, and for the hybrid
// world normal and object id, in the formats engines draw them:
// include/hmblur/engine_motion_blur.h) packed into the library's image layer and its
// velocities, as pack_engine_gbuffer packs buffers (engine_pixel.glsl): the body of
// pack_engine_images (HMB_ENGINE_IMAGE_SURFACES 1) and pack_engine_colour_images (0, without
// the normal and object-id images, which then are not bound). Each image is read with
// texelFetch and no sampler, so any sampled format serves: a depth view gives its depth, a
// UNORM or SNORM view its decoded value.
#ifndef HMB_KERNELS_ENGINE_PACK_ENGINE_IMAGES_GLSL
#define HMB_KERNELS_ENGINE_PACK_ENGINE_IMAGES_GLSL

layout(local_size_x = HMB_ENGINE_GROUP_X, local_size_y = HMB_ENGINE_GROUP_Y) in;

layout(binding = HMB_ENGINE_BINDING_COLOR) uniform texture2D colorImage;
layout(binding = HMB_ENGINE_BINDING_DEPTH) uniform texture2D depthImage;
layout(binding = HMB_ENGINE_BINDING_VELOCITY) uniform texture2D velocityImage;
layout(std430, binding = HMB_ENGINE_BINDING_SAMPLES) writeonly buffer Samples { uvec4 samples[]; };
layout(std430, binding = HMB_ENGINE_BINDING_SURFACES) writeonly buffer Surfaces { uvec4 surfaces[]; };
#if HMB_ENGINE_IMAGE_SURFACES
layout(binding = HMB_ENGINE_BINDING_NORMAL) uniform texture2D normalImage;
layout(binding = HMB_ENGINE_BINDING_OBJECT_ID) uniform utexture2D objectIdImage;
#endif
layout(std430, binding = HMB_ENGINE_BINDING_VELOCITIES) writeonly buffer Velocities { vec2 velocities[]; };
layout(push_constant) uniform Params { EngineGBufferParams params; };

#include "engine_pixel.glsl"

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const ivec2 at = ivec2(pixel);
  const uint i = pixel.y * params.width + pixel.x;
#if HMB_ENGINE_IMAGE_SURFACES
  const vec3 normal = texelFetch(normalImage, at, 0).xyz;
  const uint id = texelFetch(objectIdImage, at, 0).r;
#else
  const vec3 normal = vec3(0.0);
  const uint id = 0u;
#endif
  packEnginePixel(i, texelFetch(colorImage, at, 0).rgb, texelFetch(depthImage, at, 0).r,
                  texelFetch(velocityImage, at, 0).rg, normal, id, HMB_ENGINE_IMAGE_SURFACES != 0);
}

#endif
