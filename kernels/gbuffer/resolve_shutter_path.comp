#version 450
// Visibility buffer -> each pixel's screen path over the shutter: for the surface point seen at
// the pixel centre (the same perspective-correct barycentrics as resolve_gbuffer), where it is
// on screen at mid-shutter and at shutter open (raster/transform_shutter_path's clip
// positions), as offsets from the pixel (gbuffer_layout.h). Runs only in frames that use the
// curved motion path.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "gbuffer_layout.h"
#include "../raster/raster_layout.h"

layout(local_size_x = HMB_RESOLVE_GROUP_X, local_size_y = HMB_RESOLVE_GROUP_Y) in;

#include "../shared/texel_records.glsl"
layout(binding = HMB_SHUTTER_PATH_RESOLVE_BINDING_VISIBILITY) uniform utextureBuffer visibilityTexels;
layout(binding = HMB_SHUTTER_PATH_RESOLVE_BINDING_TRIANGLES) uniform utextureBuffer triangleTexels;
layout(binding = HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_CURRENT) uniform utextureBuffer clipCurrentTexels;
layout(binding = HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_MID) uniform utextureBuffer clipMidTexels;
layout(binding = HMB_SHUTTER_PATH_RESOLVE_BINDING_CLIP_OPEN) uniform utextureBuffer clipOpenTexels;
layout(std430, binding = HMB_SHUTTER_PATH_RESOLVE_BINDING_PATHS) writeonly buffer Paths { uvec2 paths[]; };
layout(push_constant) uniform Params { ResolveParams params; };

vec3 xyw(vec4 clip) { return clip.xyw; }

#include "clip_barycentrics.glsl"

// Offsets past the largest half keep their direction; non-finite ones never get here.
uint packOffset(vec2 d) {
  const float largest = max(abs(d.x), abs(d.y));
  return packHalf2x16(largest > 65504.0 ? d * (65504.0 / largest) : d);
}

void main() {
  const uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= params.width || pixel.y >= params.height) return;
  const uint index = pixel.y * params.width + pixel.x;
  const uint triangleId = halfRecordAt(visibilityTexels, index).x;
  if (triangleId == HMB_VIS_EMPTY) {
    paths[index] = uvec2(HMB_NO_SHUTTER_PATH);
    return;
  }
  const uvec4 tri = recordAt(triangleTexels, triangleId);
  const vec2 centre = vec2(pixel) + 0.5;
  const vec2 ndc = centre / vec2(params.width, params.height) * 2.0 - 1.0;
  const vec3 b = clipBarycentrics(xyw(floatRecordAt(clipCurrentTexels, tri.x)), xyw(floatRecordAt(clipCurrentTexels, tri.y)),
                                  xyw(floatRecordAt(clipCurrentTexels, tri.z)), ndc);
  const vec3 mid = b.x * xyw(floatRecordAt(clipMidTexels, tri.x)) + b.y * xyw(floatRecordAt(clipMidTexels, tri.y)) +
                   b.z * xyw(floatRecordAt(clipMidTexels, tri.z));
  const vec3 open = b.x * xyw(floatRecordAt(clipOpenTexels, tri.x)) + b.y * xyw(floatRecordAt(clipOpenTexels, tri.y)) +
                    b.z * xyw(floatRecordAt(clipOpenTexels, tri.z));
  const vec2 fromMid = centre - clipToPixel(mid, params.width, params.height);
  const vec2 fromOpen = centre - clipToPixel(open, params.width, params.height);
  const bool known = mid.z > 0.0 && open.z > 0.0 && !any(isnan(fromMid)) && !any(isinf(fromMid)) &&
                     !any(isnan(fromOpen)) && !any(isinf(fromOpen));
  paths[index] = known ? uvec2(packOffset(fromMid), packOffset(fromOpen)) : uvec2(HMB_NO_SHUTTER_PATH);
}
