// Layout of the hybrid method's kernels (kernels/hybrid/), the paper's section 3.2:
//   edge_mask      eqs. 1-4: moving pixels whose predicted end position lies on a different,
//                  deeper object, and whose 5x5 Sobel of depth and normal passes the edge
//                  threshold e
//   range_check    moving pixels whose range along their velocity meets the edge mask: the ray
//                  mask, as a 0/1 image (for the gathers) and a compacted pixel list
//   size_reveal_dispatch  the list's length -> the indirect dispatch of the list passes, so an
//                  empty mask dispatches nothing
//   reveal_background     per listed pixel, the first surface behind the object the raster sees
//                  there: its colour, depth, normal, velocity and object id
// Shared by the GLSL kernels and the C++ passes and reference.
#ifndef HMB_KERNELS_HYBRID_HYBRID_LAYOUT_H
#define HMB_KERNELS_HYBRID_HYBRID_LAYOUT_H

#include "../shared/glsl_cpp.h"

#define HMB_EDGE_MASK_GROUP_X 8
#define HMB_EDGE_MASK_GROUP_Y 8
#define HMB_EDGE_MASK_BINDING_NORMAL_DEPTH 0  // vec4 per pixel: world normal, w camera-space depth
#define HMB_EDGE_MASK_BINDING_VELOCITY 1      // vec2 per pixel: pixels per frame
#define HMB_EDGE_MASK_BINDING_OBJECT_ID 2     // uint per pixel
#define HMB_EDGE_MASK_BINDING_EDGES 3         // uint per pixel: 1 in the edge mask, else 0
#define HMB_EDGE_MASK_BINDING_COUNT 4

#define HMB_RANGE_CHECK_GROUP_X 8
#define HMB_RANGE_CHECK_GROUP_Y 8
#define HMB_RANGE_CHECK_BINDING_VELOCITY 0  // vec2 per pixel
#define HMB_RANGE_CHECK_BINDING_EDGES 1     // uint per pixel (edge_mask)
#define HMB_RANGE_CHECK_BINDING_MASK 2      // uint per pixel: 1 in the ray mask, else 0
#define HMB_RANGE_CHECK_BINDING_COUNTERS 3  // RayMaskCounters
#define HMB_RANGE_CHECK_BINDING_LIST 4      // uint pixel index per masked pixel, in no order
#define HMB_RANGE_CHECK_BINDING_COUNT 5

#define HMB_SIZE_REVEAL_BINDING_COUNTERS 0
#define HMB_SIZE_REVEAL_BINDING_COUNT 1

// The list passes (reveal_background and the gather's list mode) run 64 lanes per group.
#define HMB_MASK_LIST_GROUP 64

// reveal_background. Slots 2-11 hold the trace scene (kernels/trace/closest_hit.glsl).
#define HMB_REVEAL_BINDING_CAMERA_RAYS 0    // PinholeCamera at the frame time
#define HMB_REVEAL_BINDING_LIST 1           // the ray mask's pixel list
#define HMB_REVEAL_BINDING_VERTICES 12      // GpuVertex per mesh vertex
#define HMB_REVEAL_BINDING_INSTANCES 13     // GpuInstance per instance (material, previous transform)
#define HMB_REVEAL_BINDING_MATERIALS 14
#define HMB_REVEAL_BINDING_TEXELS 15
#define HMB_REVEAL_BINDING_CAMERA 16        // GpuCamera: previous view-projection, light, background
#define HMB_REVEAL_BINDING_RASTER_ID 17     // uint per pixel: the G-buffer's object id
#define HMB_REVEAL_BINDING_COUNTERS 18      // RayMaskCounters: the list's length; rays are counted into it
#define HMB_REVEAL_BINDING_COLOR 19         // vec4 per pixel: revealed colour (written at listed pixels)
#define HMB_REVEAL_BINDING_NORMAL_DEPTH 20  // vec4 per pixel: revealed normal, w depth
#define HMB_REVEAL_BINDING_VELOCITY 21      // vec2 per pixel: revealed velocity, pixels per frame
#define HMB_REVEAL_BINDING_OBJECT_ID 22     // uint per pixel: revealed object id (0: nothing behind)
#define HMB_REVEAL_BINDING_COUNT 23

// RevealParams.stop
#define HMB_REVEAL_STOP_OBJECT_ID 0u  // the first surface of another object (one trace, the object skipped whole)
#define HMB_REVEAL_STOP_LUMINANCE 1u  // the paper's mode: step past hits until the luminance differs

HMB_GPU_BEGIN

// Cleared each frame; maskCount written by range_check, the dispatch by size_reveal_dispatch
// (a VkDispatchIndirectCommand at byte offset 4), rayCount by reveal_background.
struct RayMaskCounters {
  uint maskCount;
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
  uint rayCount;  // closest-hit traces the reveal made
  uint pad0;
  uint pad1;
  uint pad2;
};

struct EdgeMaskParams {
  uint width;
  uint height;
  float velocityScale;  // q (pixels per frame) -> per-exposure displacement: E * fps
  float maxSpeed;       // displacements are clamped to this length (the image's larger side)
  float softZExtent;    // eq. 2: the end position must be deeper by more than this
  float edgeThreshold;  // e: eq. 4's x_n must exceed it
  uint pad0;
  uint pad1;
};

struct RangeCheckParams {
  uint width;
  uint height;
  float velocityScale;
  float maxSpeed;
};

struct RevealParams {
  uint width;
  uint height;
  uint instanceCount;
  uint stop;                 // HMB_REVEAL_STOP_*
  uint maxRecursion;         // luminance mode: hits stepped past at most (>= 1)
  float luminanceThreshold;  // luminance mode: relative difference that ends the recursion
  float tMin;                // the near plane's depth
  float tMax;                // the far plane's depth
  float backgroundDepth;     // depth written where nothing is behind (the G-buffer's far value)
  uint pad0;
  uint pad1;
  uint pad2;
};

HMB_GPU_END

HMB_CHECK_SIZE(RayMaskCounters, 32)
HMB_CHECK_SIZE(EdgeMaskParams, 32)
HMB_CHECK_SIZE(RangeCheckParams, 16)
HMB_CHECK_SIZE(RevealParams, 48)

#endif
