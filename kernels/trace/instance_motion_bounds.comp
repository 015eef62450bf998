#version 450
// The box the top level holds for each instance: its mesh's root box carried into the world
// at every shutter time, merged, so that a ray traced at any of those times finds it. The root
// box is the packed one traversal tests (it holds the exact one).
#extension GL_GOOGLE_include_directive : require
#include "../shared/float_controls.glsl"
#include "trace_layout.h"
#include "../shared/indexing.glsl"
#include "../bvh/packed_node.glsl"

layout(local_size_x = HMB_TRACE_GROUP) in;

layout(std430, binding = HMB_MOTION_BOUNDS_BINDING_MESH_NODES) readonly buffer MeshNodes { uvec4 meshNodes[]; };
layout(std430, binding = HMB_MOTION_BOUNDS_BINDING_MESH_FRAMES) readonly buffer MeshFrames { BvhFrame meshFrames[]; };
layout(std430, binding = HMB_MOTION_BOUNDS_BINDING_INSTANCES) readonly buffer Instances { TraceInstance instances[]; };
layout(std430, binding = HMB_MOTION_BOUNDS_BINDING_TRANSFORMS) readonly buffer Transforms { InstanceTransform transforms[]; };
layout(std430, binding = HMB_MOTION_BOUNDS_BINDING_BOXES) writeonly buffer Boxes { BvhBox boxes[]; };
layout(push_constant) uniform Params { TraceParams params; };

void main() {
  const uint i = linearInvocationIndex(HMB_TRACE_GROUP);
  if (i >= params.instanceCount) return;
  const uint mesh = instances[i].mesh;
  const uvec4 root = meshNodes[mesh];
  const BvhFrame frame = meshFrames[mesh];
  const vec3 lo = packedLower(root, frame), hi = packedUpper(root, frame);
  vec3 worldLo = vec3(uintBitsToFloat(0x7f800000u)), worldHi = -worldLo;
  if (all(lessThanEqual(lo, hi))) {
    // An affine map of a box: the centre moves, the half extent goes through |M|.
    const vec3 centre = 0.5 * (lo + hi), halfExtent = 0.5 * (hi - lo);
    for (uint time = 0; time < params.timeCount; ++time) {
      const mat4 m = transforms[i * params.timeCount + time].worldFromObject;
      const vec3 c = (m * vec4(centre, 1.0)).xyz;
      const vec3 h = abs(m[0].xyz) * halfExtent.x + abs(m[1].xyz) * halfExtent.y + abs(m[2].xyz) * halfExtent.z;
      // Widened by a relative 2^-20 so that rounding here never leaves a transformed vertex out.
      const vec3 pad = (abs(c) + h) * (1.0 / 1048576.0);
      worldLo = min(worldLo, c - h - pad);
      worldHi = max(worldHi, c + h + pad);
    }
  }
  boxes[i].min = vec4(worldLo, 0.0);
  boxes[i].max = vec4(worldHi, 0.0);
}
