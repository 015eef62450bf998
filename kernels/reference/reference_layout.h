// Layouts of the reference renderer (Cook et al. 1984 distributed ray tracing): for every
// pixel, rays at stratified shutter times, each traced against the scene at its own time and
// shaded by the shared shading function, summed per pixel in a fixed order (a tree of pairwise
// sums, runtime/passes/reference_sum_tree.h) and averaged at the end.
#ifndef HMB_KERNELS_REFERENCE_REFERENCE_LAYOUT_H
#define HMB_KERNELS_REFERENCE_REFERENCE_LAYOUT_H

#include "../shared/glsl_cpp.h"
#include "../trace/trace_layout.h"
#include "../shared/scene_layout.h"

#define HMB_REFERENCE_GROUP_X 8
#define HMB_REFERENCE_GROUP_Y 8
#define HMB_REFERENCE_AVERAGE_GROUP 64

// accumulate_sample
#define HMB_REFERENCE_BINDING_CAMERAS 0  // PinholeCamera per shutter time of the batch
#define HMB_REFERENCE_BINDING_SUMS 1     // vec4 per pixel per slot: the sum tree's nodes (rgb sum, w count)
#define HMB_REFERENCE_BINDING_PIXELS 2   // uint pixel index per entry: the pixels to sample (list mode)
// The trace scene (trace/trace_scene_bindings.glsl), then the scene's shading buffers
// (shared/scene_bindings.glsl).
#define HMB_REFERENCE_BINDING_TRACE_SCENE 3
#define HMB_REFERENCE_BINDING_SCENE (HMB_REFERENCE_BINDING_TRACE_SCENE + HMB_TRACE_SCENE_BINDINGS)
#define HMB_REFERENCE_BINDING_COUNT (HMB_REFERENCE_BINDING_SCENE + HMB_SCENE_BINDINGS)

// find_moving_pixels: pixels whose ray meets the box some moving instance sweeps over the
// shutter. Only they can change over the shutter when the camera stands still.
// An invocation tests every box in one loop, at most this many: llvmpipe 22.3 ends an
// invocation's loops after 65535 rounds in all, silently. With more moving instances every
// pixel is listed untested (it takes every sample: the image is the same, the saving gone).
#define HMB_MOVING_PIXELS_MAX_BOXES 57344u
#define HMB_MOVING_PIXELS_GROUP_X 8
#define HMB_MOVING_PIXELS_GROUP_Y 8
#define HMB_MOVING_PIXELS_BINDING_CAMERAS 0  // PinholeCamera (the first is used)
#define HMB_MOVING_PIXELS_BINDING_BOXES 1    // vec4 lower, vec4 upper per moving instance
#define HMB_MOVING_PIXELS_BINDING_COUNTER 2  // uint: entries in the list
#define HMB_MOVING_PIXELS_BINDING_LIST 3     // uint pixel index per entry
#define HMB_MOVING_PIXELS_BINDING_COUNT 4

// fold_sums: adds slots of the sum tree two at a time, in the order a list gives
#define HMB_FOLD_SUMS_GROUP 64
#define HMB_FOLD_SUMS_BINDING_SUMS 0  // vec4 per pixel per slot
#define HMB_FOLD_SUMS_BINDING_OPS 1   // uvec4 per addition: slot x = slot x + slot y
#define HMB_FOLD_SUMS_BINDING_COUNT 2

// average_samples
#define HMB_AVERAGE_BINDING_SUMS 0   // vec4 per pixel of a band of rows per slot
#define HMB_AVERAGE_BINDING_COLOR 1  // vec4 per pixel: the mean, linear RGB, a = 1
#define HMB_AVERAGE_BINDING_COUNT 2

// ReferenceSampleParams.flags
#define HMB_REFERENCE_PIXEL_JITTER 1u  // a random point in the pixel instead of its centre
#define HMB_REFERENCE_PIXEL_LIST 2u    // sample the pixels of the list (entries: pixelCount), not the image

HMB_GPU_BEGIN

struct ReferenceSampleParams {
  uint width;
  uint height;
  uint time;         // index of this sample's shutter time in the batch (cameras, transforms)
  uint sampleIndex;  // global index of the sample: seeds the pixel jitter
  uint seed;
  uint flags;        // HMB_REFERENCE_*
  uint instanceCount;
  uint timeCount;    // shutter times in the batch
  float tMin;        // the near plane's depth
  float tMax;        // the far plane's depth
  uint listLength;   // HMB_REFERENCE_PIXEL_LIST: entries in the pixel list
  // The sample's place in the sum tree: the sums in slots foldSlots[0 .. foldCount) are added
  // before it in turn (each the left neighbour of what it has so far), and the result goes to
  // slot targetSlot.
  uint foldCount;
  uint targetSlot;
  // The band of rows whose sums the bound buffer holds (runtime/passes/reference_stage.h's
  // DeviceSumSlots): slot s of pixel (x, y) is entry s * bandRows * width + (y - bandFirstRow)
  // * width + x. Outside list mode the dispatch covers the band's rows alone.
  uint bandFirstRow;
  uint bandRows;
  uint pad0;
  uvec4 foldSlots[2];
};

struct FoldSumsParams {
  uint pixelCount;
  uint opCount;
  uint pad0;
  uint pad1;
};

struct MovingPixelsParams {
  uint width;
  uint height;
  uint boxCount;
  uint pad0;
  float tMin;
  float tMax;
  uint pad1;
  uint pad2;
};

struct AverageParams {
  uint pixelCount;  // of the band of rows the sums hold; each pixel's sample count is its sum's w
  uint sumSlot;     // the slot holding the total
  uint firstPixel;  // the band's first pixel in the colour buffer
  uint pad2;
};

HMB_GPU_END

HMB_CHECK_SIZE(ReferenceSampleParams, 96)
HMB_CHECK_SIZE(FoldSumsParams, 16)
HMB_CHECK_SIZE(AverageParams, 16)
HMB_CHECK_SIZE(MovingPixelsParams, 32)

#endif
