// The trace scene as a kernel binds it, from its binding HMB_TRACE_SCENE_BINDING on (defined
// by the including kernel): the 10 buffers, or in builds with HMB_BIND_BY_ADDRESS (devices
// with few storage-buffer bindings) one TraceSceneTable of their addresses. Either way the
// kernels read the same names: topPrimitives[i], ..., and topNode(i), meshNode(i),
// leafTriangle(i), traceInstanceAt(i), objectFromWorldAt(i) and meshFrameAt(i) for the arrays
// a ray reads at its own addresses.
// Those six are uniform texel buffers in the plain build (shared/texel_records.glsl: a faster
// trace on lavapipe, bench/results/texel-reads/; on GPUs the read-only cached path that BVH
// traversal has long used for nodes and triangles).
#ifndef HMB_KERNELS_TRACE_TRACE_SCENE_BINDINGS_GLSL
#define HMB_KERNELS_TRACE_TRACE_SCENE_BINDINGS_GLSL

#include "trace_layout.h"

#ifdef HMB_BIND_BY_ADDRESS
layout(std430, binding = HMB_TRACE_SCENE_BINDING) readonly buffer TraceScene { TraceSceneTable traceScene; };
#define topNodes traceScene.topNodes.v
#define topPrimitives traceScene.topPrimitives.v
#define traceInstances traceScene.instances.v
#define transforms traceScene.transforms.v
#define meshNodes traceScene.meshNodes.v
#define meshPrimitives traceScene.meshPrimitives.v
#define leafTriangles traceScene.leafTriangles.v
#define topFrame traceScene.topFrame.v[0]
#define meshFrames traceScene.meshFrames.v
#define traceStatus traceScene.status.v
uvec4 topNode(uint i) { return topNodes[i]; }
uvec4 meshNode(uint i) { return meshNodes[i]; }
TraceInstance traceInstanceAt(uint i) { return traceInstances[i]; }
mat4 objectFromWorldAt(uint i) { return transforms[i].objectFromWorld; }
BvhFrame meshFrameAt(uint mesh) { return meshFrames[mesh]; }
vec4 leafTriangle(uint i) { return leafTriangles[i]; }
#else
#include "../shared/texel_records.glsl"
layout(binding = HMB_TRACE_SCENE_BINDING + 0) uniform utextureBuffer topNodeTexels;
layout(std430, binding = HMB_TRACE_SCENE_BINDING + 1) readonly buffer TopPrimitives { uint topPrimitives[]; };
layout(binding = HMB_TRACE_SCENE_BINDING + 2) uniform utextureBuffer traceInstanceTexels;  // 1 record each
layout(binding = HMB_TRACE_SCENE_BINDING + 3) uniform utextureBuffer transformTexels;      // 8 records each
layout(binding = HMB_TRACE_SCENE_BINDING + 4) uniform utextureBuffer meshNodeTexels;
layout(std430, binding = HMB_TRACE_SCENE_BINDING + 5) readonly buffer MeshPrimitives { uint meshPrimitives[]; };
// Each triangle's three vertices in the leaves' order (entry e at 3e..3e+2): a leaf's triangles
// are three loads each, with no indirection through vertex indices.
layout(binding = HMB_TRACE_SCENE_BINDING + 6) uniform utextureBuffer leafTriangleTexels;
layout(std430, binding = HMB_TRACE_SCENE_BINDING + 7) readonly buffer TopFrame { BvhFrame topFrame; };
layout(binding = HMB_TRACE_SCENE_BINDING + 8) uniform utextureBuffer meshFrameTexels;  // 2 records each
// The traces' status (HMB_TRACE_STATUS_WORDS), the one buffer they write.
layout(std430, binding = HMB_TRACE_SCENE_BINDING + 9) buffer TraceStatus { uint traceStatus[]; };
uvec4 topNode(uint i) { return recordAt(topNodeTexels, i); }
TraceInstance traceInstanceAt(uint i) {
  const uvec4 r = recordAt(traceInstanceTexels, i);
  return TraceInstance(r.x, r.y, r.z, r.w);
}
mat4 objectFromWorldAt(uint i) { return mat4RecordsAt(transformTexels, 8u * i + 4u); }  // records 4-7 of 8
BvhFrame meshFrameAt(uint mesh) {
  return BvhFrame(floatRecordAt(meshFrameTexels, 2u * mesh), floatRecordAt(meshFrameTexels, 2u * mesh + 1u));
}
uvec4 meshNode(uint i) { return recordAt(meshNodeTexels, i); }
vec4 leafTriangle(uint i) { return floatRecordAt(leafTriangleTexels, i); }
#endif

#endif
