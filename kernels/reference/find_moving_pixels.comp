#version 450
// Lists the pixels whose camera ray meets the box some moving instance sweeps over the
// shutter's sample times. With the camera standing still, every other pixel sees the same
// surface at every time, so one sample of it is exact and the reference samples only the list.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "reference_layout.h"
#include "../trace/ray_tests.glsl"

layout(local_size_x = HMB_MOVING_PIXELS_GROUP_X, local_size_y = HMB_MOVING_PIXELS_GROUP_Y) in;

layout(std430, binding = HMB_MOVING_PIXELS_BINDING_CAMERAS) readonly buffer Cameras { PinholeCamera cameras[]; };
layout(std430, binding = HMB_MOVING_PIXELS_BINDING_BOXES) readonly buffer Boxes { vec4 boxes[]; };
layout(std430, binding = HMB_MOVING_PIXELS_BINDING_COUNTER) buffer Counter { uint listLength; };
layout(std430, binding = HMB_MOVING_PIXELS_BINDING_LIST) writeonly buffer List { uint list[]; };
layout(push_constant) uniform Params { MovingPixelsParams params; };

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const PinholeCamera cam = cameras[0];
  const PreparedRay r = prepareRay(cam.eye.xyz, pinholeRayDirection(cam, vec2(pixel) + 0.5, params.width, params.height));
  // A loop round a box: past HMB_MOVING_PIXELS_MAX_BOXES the pixel is listed untested.
  const uint tested = min(params.boxCount, HMB_MOVING_PIXELS_MAX_BOXES);
  bool moving = tested < params.boxCount;
  for (uint b = 0; b < tested && !moving; ++b)
    moving = r.valid && intersectBox(r, boxes[2 * b].xyz, boxes[2 * b + 1].xyz, params.tMin, params.tMax);
  if (moving) list[atomicAdd(listLength, 1u)] = pixel.y * params.width + pixel.x;
}
