#version 450
// Clip-space position of every instance vertex at mid-shutter (t - E/2) and at shutter open
// (t - E): with transform_vertices' position at t, three points of its screen path, from which
// the curved motion path (resolve_shutter_path, the gathers) takes a quadratic. Runs only in
// frames that use that path.
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "raster_layout.h"
#include "../shared/scene_layout.h"
#include "../shared/indexing.glsl"

layout(local_size_x = HMB_RASTER_GROUP) in;
layout(constant_id = HMB_SPEC_SHUTTER_PATH_DEFORMED) const bool kDeformed = false;

layout(std430, binding = HMB_SHUTTER_PATH_BINDING_VERTICES) readonly buffer Vertices { GpuVertex vertices[]; };
layout(std430, binding = HMB_SHUTTER_PATH_BINDING_INSTANCE_VERTICES) readonly buffer InstanceVertices { GpuInstanceVertex instanceVertices[]; };
layout(std430, binding = HMB_SHUTTER_PATH_BINDING_SHUTTER_CLIP) readonly buffer ShutterClips { GpuShutterClip shutterClips[]; };
layout(std430, binding = HMB_SHUTTER_PATH_BINDING_PREVIOUS_VERTICES) readonly buffer PreviousVertices { GpuVertex previousVertices[]; };
layout(std430, binding = HMB_SHUTTER_PATH_BINDING_CLIP_MID) writeonly buffer ClipMid { vec4 clipMid[]; };
layout(std430, binding = HMB_SHUTTER_PATH_BINDING_CLIP_OPEN) writeonly buffer ClipOpen { vec4 clipOpen[]; };
layout(push_constant) uniform Params { ShutterPathParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_RASTER_GROUP);
  if (i >= params.vertexCount) return;
  const GpuInstanceVertex iv = instanceVertices[i];
  const vec4 p = vertices[iv.meshVertex].position;
  // A deformation is known at t and t - 1/fps only: in between (and before) it moves straight.
  const vec4 previous = kDeformed ? previousVertices[iv.meshVertex].position : p;
  const vec4 mid = kDeformed ? mix(p, previous, params.midFrames) : p;
  const vec4 open = kDeformed ? mix(p, previous, params.openFrames) : p;
  clipMid[i] = shutterClips[iv.instance].clipMid * mid;
  clipOpen[i] = shutterClips[iv.instance].clipOpen * open;
}
