// Layout of the reveal and the composite (kernels/reveal/), the paper's section 3.2, steps 3 to
// 5, over the ray mask's list (kernels/ray_mask/):
//   reveal_background     per listed pixel, the first surface behind the object the raster sees
//                  there: its colour, depth, normal, velocity and object id
//   gather_background     the background layer (the raster, the revealed surfaces where
//                  revealed) blurred at the listed pixels; with the coverage composite,
//                  blended under the mask's foreground there
//   composite      the raster layer's gather with the blurred background composited in at
//                  mask pixels (weights), or the mask's foreground at those not revealed
//                  (coverage)
// Shared by the GLSL kernels and the C++ passes and reference.
#ifndef HMB_KERNELS_REVEAL_REVEAL_LAYOUT_H
#define HMB_KERNELS_REVEAL_REVEAL_LAYOUT_H

#include "../ray_mask/ray_mask_layout.h"
#include "../shared/scene_layout.h"
#include "../trace/trace_layout.h"

// reveal_background
#define HMB_REVEAL_BINDING_CAMERA_RAYS 0  // PinholeCamera at the frame time
#define HMB_REVEAL_BINDING_LIST 1         // the ray mask's pixel list
#define HMB_REVEAL_BINDING_COUNTERS 2     // RayMaskCounters: the list's length; rays are counted into it
// The G-buffer (shared/layer_bindings.glsl, read as texels): its object ids and depths.
#define HMB_REVEAL_BINDING_RASTER 3
// The trace scene (trace/trace_scene_bindings.glsl), the scene's shading buffers
// (shared/scene_bindings.glsl), then the revealed layer, written at the listed pixels
// (shared/layer_bindings.glsl; object id 0 where nothing is behind).
#define HMB_REVEAL_BINDING_TRACE_SCENE (HMB_REVEAL_BINDING_RASTER + HMB_LAYER_BINDINGS)
#define HMB_REVEAL_BINDING_SCENE (HMB_REVEAL_BINDING_TRACE_SCENE + HMB_TRACE_SCENE_BINDINGS)
#define HMB_REVEAL_BINDING_REVEALED (HMB_REVEAL_BINDING_SCENE + HMB_SCENE_BINDINGS)
#define HMB_REVEAL_BINDING_COUNT (HMB_REVEAL_BINDING_REVEALED + HMB_LAYER_BINDINGS)
// Read through texel views (counted in kernels/manifest.h): the layer, the trace scene's and the scene's records.

// gather_background: the background layer (the raster, the revealed layer where the mask says
// HMB_MASK_REVEALED) blurred at the listed pixels; one invocation per list entry. With the
// coverage composite (HMB_SPEC_BACKGROUND_GATHER_COVERAGE) it also blends the result under
// mask_coverage's foreground and writes the hybrid's image there.
#define HMB_BACKGROUND_GATHER_BINDING_NEIGHBOR_MAX 0  // vec4 per tile
#define HMB_BACKGROUND_GATHER_BINDING_MASK 1          // uint per pixel: HMB_MASK_*
#define HMB_BACKGROUND_GATHER_BINDING_LIST 2          // the ray mask's pixel list
#define HMB_BACKGROUND_GATHER_BINDING_COUNTERS 3      // RayMaskCounters: the list's length
#define HMB_BACKGROUND_GATHER_BINDING_OUTPUT 4        // vec4 per pixel, written at listed pixels
#define HMB_BACKGROUND_GATHER_BINDING_RASTER 5        // the G-buffer (shared/layer_bindings.glsl)
#define HMB_BACKGROUND_GATHER_BINDING_REVEALED (HMB_BACKGROUND_GATHER_BINDING_RASTER + HMB_LAYER_BINDINGS)
// The raster layer's shutter paths (gbuffer/gbuffer_layout.h), read along curved paths.
#define HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS (HMB_BACKGROUND_GATHER_BINDING_REVEALED + HMB_LAYER_BINDINGS)
// vec4 per pixel: mask_coverage's (mean colour, alpha), read with the coverage composite.
#define HMB_BACKGROUND_GATHER_BINDING_COVERAGE (HMB_BACKGROUND_GATHER_BINDING_SHUTTER_PATHS + 1)
#define HMB_BACKGROUND_GATHER_BINDING_COUNT (HMB_BACKGROUND_GATHER_BINDING_COVERAGE + 1)
// Both layers, the paths and the coverage, read as uniform texel buffers (counted in kernels/manifest.h).

// composite: the weights form at every pixel of the ray mask (all at the list's front), one
// invocation per entry; the coverage form at the list's back (the mask pixels not revealed, read
// from the list's end inwards), gather_background having blended its front. The post-process
// gather has written every pixel before.
#define HMB_COMPOSITE_BINDING_NEIGHBOR_MAX 0  // vec4 per tile
#define HMB_COMPOSITE_BINDING_LIST 1          // the ray mask's pixel list
#define HMB_COMPOSITE_BINDING_BACKGROUND 2    // vec4 per pixel: the blurred background (weights form)
#define HMB_COMPOSITE_BINDING_OUTPUT 3        // vec4 per pixel, written at mask pixels
#define HMB_COMPOSITE_BINDING_RASTER 4        // the G-buffer (shared/layer_bindings.glsl)
// The G-buffer's shutter paths (gbuffer/gbuffer_layout.h), read along curved paths.
#define HMB_COMPOSITE_BINDING_SHUTTER_PATHS (HMB_COMPOSITE_BINDING_RASTER + HMB_LAYER_BINDINGS)
#define HMB_COMPOSITE_BINDING_COUNTERS (HMB_COMPOSITE_BINDING_SHUTTER_PATHS + 1)  // RayMaskCounters
// vec4 per pixel: mask_coverage's (mean colour, alpha), read by the coverage form.
#define HMB_COMPOSITE_BINDING_COVERAGE (HMB_COMPOSITE_BINDING_COUNTERS + 1)
#define HMB_COMPOSITE_BINDING_COUNT (HMB_COMPOSITE_BINDING_COVERAGE + 1)
// The G-buffer layer and its paths, the neighbour-max, the background and the coverage: read as
// uniform texel buffers (counted in kernels/manifest.h).
// The curved path's code and the range, compiled into the background gather and the composite
// only as the frame takes them (as mblur/gather.comp's): on a CPU device the code of a branch no
// lane takes still runs, and the curved path's reads at every sample cost the background gather
// most of its time (bench/results/hybrid-kernel-shapes/).
#define HMB_SPEC_COMPOSITE_CURVED_PATH 0
#define HMB_SPEC_COMPOSITE_ADAPTED_RANGE 1
#define HMB_SPEC_COMPOSITE_COVERAGE 2  // true: the coverage form (the list's back); false: the weights form
#define HMB_SPEC_BACKGROUND_GATHER_CURVED_PATH 0
#define HMB_SPEC_BACKGROUND_GATHER_ADAPTED_RANGE 1
// true: the coverage composite blended where the background is gathered, at the revealed pixels
// (the composite pass takes the others, a lane's gather code never run for them); false: the
// background alone, for the weights form's composite.
#define HMB_SPEC_BACKGROUND_GATHER_COVERAGE 2
// reveal_background's stop, a specialization constant (the build has only its own mode's code:
// on a CPU device the luminance mode's traces and shading ran, without a lane, for every ray of
// the object-id mode, a good part of the reveal: bench/results/hybrid-kernel-shapes/)
#define HMB_SPEC_REVEAL_STOP HMB_SPEC_KERNEL_CONSTANTS_FIRST
#define HMB_REVEAL_STOP_OBJECT_ID 0u  // the first surface of another object (one trace, the object skipped whole)
#define HMB_REVEAL_STOP_LUMINANCE 1u  // the paper's mode: step past hits until the luminance differs

HMB_GPU_BEGIN

struct RevealParams {
  uint width;
  uint height;
  uint instanceCount;
  uint pad0;
  uint maxRecursion;         // luminance mode: hits stepped past at most (>= 1)
  float luminanceThreshold;  // luminance mode: relative difference that ends the recursion
  float tMin;                // the near plane's depth
  float tMax;                // the far plane's depth
  float backgroundDepth;     // depth written where nothing is behind (the G-buffer's far value)
  uint timeCount;            // the trace scene's times; the reveal traces the first, the frame's
  uint pad1;
  uint pad2;
};

HMB_GPU_END

HMB_CHECK_SIZE(RevealParams, 48)

#endif
