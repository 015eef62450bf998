// Layouts of the ray tracing kernels: rays in, closest hits out, through a two-level BVH (a
// top level over instances, rebuilt per frame over their motion bounds; a bottom level per
// mesh, built once). Instances carry their transform at each of the frame's shutter times; a
// ray names the time it is traced at, and is carried into the instance's space with that
// time's transform, so any motion, rotation included, is traced exactly at those times.
#ifndef HMB_KERNELS_TRACE_TRACE_LAYOUT_H
#define HMB_KERNELS_TRACE_TRACE_LAYOUT_H

#include "../bvh/bvh_build_layout.h"
#include "../shared/glsl_cpp.h"

#define HMB_TRACE_GROUP 64

// The trace scene takes 10 binding numbers (trace_scene_bindings.glsl); a kernel that traces
// puts it after its own bindings. HMB_BIND_BY_ADDRESS builds bind one table of addresses at the
// first and leave the others unused, so both builds keep the same numbers for the host.
#define HMB_TRACE_SCENE_BUFFERS 10
#define HMB_TRACE_SCENE_BINDINGS HMB_TRACE_SCENE_BUFFERS
// Of those, the top-level nodes, the instances' records and transforms, the mesh nodes, the
// leaf triangles and the mesh frames are uniform texel buffers in the plain build
// (trace_scene_bindings.glsl says why); the rest storage buffers.
#define HMB_TRACE_SCENE_TEXEL_BUFFERS 6
// The trace status the traces write (the last of the trace scene's buffers), in words: word 0
// counts the traces the driver's loop limit cut short (closest_hit.glsl).
#define HMB_TRACE_STATUS_WORDS 4
#define HMB_TRACE_STATUS_CUT_TRACES 0

// trace_rays
#define HMB_TRACE_BINDING_RAYS 0  // TraceRay[]
#define HMB_TRACE_BINDING_HITS 1  // BvhHit[], one per ray
#define HMB_TRACE_BINDING_SCENE 2
#define HMB_TRACE_BINDING_COUNT (HMB_TRACE_BINDING_SCENE + HMB_TRACE_SCENE_BINDINGS)

// instance_motion_bounds: the boxes the top level is built over
#define HMB_MOTION_BOUNDS_BINDING_MESH_NODES 0
#define HMB_MOTION_BOUNDS_BINDING_INSTANCES 1
#define HMB_MOTION_BOUNDS_BINDING_TRANSFORMS 2
#define HMB_MOTION_BOUNDS_BINDING_BOXES 3  // BvhBox per instance
#define HMB_MOTION_BOUNDS_BINDING_MESH_FRAMES 4
#define HMB_MOTION_BOUNDS_BINDING_COUNT 5

// TraceParams.flags: skip the back faces of single-sided instances, as the rasterizer does
// (the renderer's rays); without it every face is hit (tests against brute force and Embree).
#define HMB_TRACE_CULL_BACK_FACES 1u

// Pending subtrees one walk through a tree keeps (closest_hit.glsl): one per level below the
// root, which the builder bounds, so no walk runs out.
#define HMB_TRACE_STACK_SIZE HMB_BVH_MAX_DEPTH

// Specialization constant of every kernel that traces (closest_hit.glsl): false builds it for a
// scene of exactly one instance, whose tree rays then enter directly, with no top level over
// it. Id 1: the shading kernels that trace use 0 (HMB_SPEC_TEXTURE_PATH).
#define HMB_SPEC_TRACE_TOP_LEVEL 1
// A shading kernel's own specialization constants take ids from here on (ShadingKernel).
#define HMB_SPEC_KERNEL_CONSTANTS_FIRST 2

// TraceInstance.flags
#define HMB_TRACE_INSTANCE_SINGLE_SIDED 1u  // its material is not double-sided

HMB_GPU_BEGIN

struct TraceParams {
  uint rayCount;
  uint instanceCount;
  uint timeCount;  // shutter times each instance has a transform for
  uint flags;      // HMB_TRACE_*
};

// origin + t * direction for t in [tMin, tMax], at shutter time index `time`.
struct TraceRay {
  vec4 originTMin;     // xyz origin, w tMin
  vec4 directionTMax;  // xyz direction (need not be unit), w tMax
  uint time;           // index of the shutter time (clamped to the last)
  uint ignoreObjectId; // hits on this object are skipped (HMB_IGNORE_NONE: none)
  uint pad0;
  uint pad1;
};

// The pinhole camera at one shutter time (the reference and the ray reveal). A pixel's ray is eye + t * (forward + x * right +
// y * down) with x, y in [-1, 1] across the image, so t is the camera-space depth of a hit and
// the rasterizer's near and far planes are t limits.
struct PinholeCamera {
  vec4 eye;
  vec4 right;    // world-space, scaled so x = 1 is the right edge of the image
  vec4 down;     // world-space, scaled so y = 1 is the bottom edge
  vec4 forward;  // world-space view direction (unit in camera units)
};

struct TraceInstance {
  uint mesh;      // its bottom-level tree is rooted at mesh node `mesh`
  uint objectId;
  uint flags;     // HMB_TRACE_INSTANCE_*
  uint pad0;
};

struct InstanceTransform {
  mat4 worldFromObject;
  mat4 objectFromWorld;
};

HMB_GPU_END

#ifndef __cplusplus
// The direction of the camera ray through image position `position` (pixels; a centre is
// integer + 0.5) of a width x height image: the one pinhole the reveal, the reference and its
// moving-pixel search all shoot through (trace_scene.h builds the camera from the raster's).
vec3 pinholeRayDirection(PinholeCamera camera, vec2 position, uint width, uint height) {
  const vec2 ndc = position / vec2(width, height) * 2.0 - 1.0;
  return camera.forward.xyz + ndc.x * camera.right.xyz + ndc.y * camera.down.xyz;
}
#endif

#ifdef HMB_ADDRESS_TABLES
#ifndef __cplusplus
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer PackedNodesRef { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer WordsRef { uint v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer TraceInstancesRef { TraceInstance v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer InstanceTransformsRef { InstanceTransform v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Uvec4sRef { uvec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer Vec4sRef { vec4 v[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer BvhFramesRef { BvhFrame v[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) buffer TraceStatusRef { uint v[]; };
#endif

HMB_GPU_BEGIN

// The trace scene's buffers by device address, in the order of their bindings
// (runtime/device_scene/trace_scene.h writes it).
struct TraceSceneTable {
  HMB_REFERENCE(PackedNodesRef) topNodes;           // over instances
  HMB_REFERENCE(WordsRef) topPrimitives;            // instance per leaf entry
  HMB_REFERENCE(TraceInstancesRef) instances;
  HMB_REFERENCE(InstanceTransformsRef) transforms;  // [instance * timeCount + time]
  HMB_REFERENCE(PackedNodesRef) meshNodes;          // of every mesh, mesh m's root at node m
  HMB_REFERENCE(WordsRef) meshPrimitives;           // triangle per leaf entry (the scene's numbering)
  HMB_REFERENCE(Vec4sRef) leafTriangles;            // 3 per leaf entry: vertex xyz, its index in w's bits
  HMB_REFERENCE(BvhFramesRef) topFrame;             // one
  HMB_REFERENCE(BvhFramesRef) meshFrames;           // one per mesh
  HMB_REFERENCE(TraceStatusRef) status;             // HMB_TRACE_STATUS_WORDS, written
};

HMB_GPU_END

HMB_CHECK_SIZE(TraceSceneTable, 80)
#endif
HMB_CHECK_SIZE(TraceParams, 16)
HMB_CHECK_SIZE(TraceRay, 48)
HMB_CHECK_SIZE(TraceInstance, 16)
HMB_CHECK_SIZE(InstanceTransform, 128)
HMB_CHECK_SIZE(PinholeCamera, 64)

#endif
