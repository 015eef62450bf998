// The blurred colour (a vec4 per pixel, row 0 at the top) written into the engine's storage
// image, alpha 1: the body of write_output_rgba16f and write_output_rgba32f, which differ only
// in the image's format (a storage image's format is the shader's, HMB_OUTPUT_FORMAT).
#ifndef HMB_KERNELS_ENGINE_WRITE_OUTPUT_IMAGE_GLSL
#define HMB_KERNELS_ENGINE_WRITE_OUTPUT_IMAGE_GLSL

layout(local_size_x = HMB_ENGINE_GROUP_X, local_size_y = HMB_ENGINE_GROUP_Y) in;

layout(std430, binding = HMB_ENGINE_OUTPUT_BINDING_COLOR) readonly buffer Color { vec4 color[]; };
layout(binding = HMB_ENGINE_OUTPUT_BINDING_IMAGE, HMB_OUTPUT_FORMAT) writeonly uniform image2D outputImage;
layout(push_constant) uniform Params { EngineOutputParams params; };

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  imageStore(outputImage, ivec2(pixel), vec4(color[pixel.y * params.width + pixel.x].rgb, 1.0));
}

#endif
