// Layout of the shutter rays (kernels/shutter_rays/), this project's addition to the paper: at
// the moving pixels whose path over the shutter crosses another object or a colour step, a few
// camera rays at stratified shutter times, where the single frame the gathers read holds no
// sub-pixel edge positions:
//   list_moving_tiles     tiles of the gather's tile-max whose fastest pixel moves half a
//                  pixel or more (the whole mask's tile-max lists them itself): only there can a
//                  pixel's displacement end on another pixel
//   list_shutter_rays     pixels of the moving tiles whose path crosses another object or a
//                  colour step, listed with the rays each takes (a power of two)
//   select_ray_budget     with a ray budget: where it runs out, first among the listed rays per
//                  priority bucket (the threshold bucket), then among that bucket's rays per range
//                  of pixel indices (ties go to the lower pixel indices: the same pixels every run)
//   tally_budget_ties     with a ray budget: the threshold bucket's rays per range of pixels
//   keep_budgeted_rays    with a ray budget: the listed pixels above the threshold bucket, and
//                  those of it in the ranges that fit, in a list of their own
//   trace_shutter_rays    per listed (or kept) pixel, camera rays at that many shutter times,
//                  each through the scene at its own time; their mean replaces the composite's colour
// Shared by the GLSL kernels and the C++ passes and reference.
#ifndef HMB_KERNELS_SHUTTER_RAYS_SHUTTER_RAYS_LAYOUT_H
#define HMB_KERNELS_SHUTTER_RAYS_SHUTTER_RAYS_LAYOUT_H

#include "../ray_mask/ray_mask_layout.h"
#include "../shared/scene_layout.h"
#include "../trace/trace_layout.h"

// list_moving_tiles: one invocation per tile; beside the shutter rays alone (the whole mask's
// tile-max lists the moving tiles as it writes them).
#define HMB_MOVING_TILES_GROUP 64
#define HMB_MOVING_TILES_BINDING_TILE_MAX 0  // vec4 per tile (kernels/mblur/mblur_layout.h), z the speed
#define HMB_MOVING_TILES_BINDING_COUNTERS 1  // RayMaskCounters
#define HMB_MOVING_TILES_BINDING_LIST 2      // uint tile index per moving tile, in no order
#define HMB_MOVING_TILES_BINDING_COUNT 3

// list_shutter_rays: an 8 x 8 group per block of the moving tiles, a pixel a lane, on a
// GPU; on a CPU device HMB_SHUTTER_LIST_CPU_GROUPS groups, each a run of consecutive blocks as
// the range check's, at most loopBudget / (s + 6) blocks for a walk speed s (a block's
// pixels take at most s + 3 rounds, a tile 2 more). A group per tile, its lanes striding over
// it, passed the budget with tiles of 128 px and walks of 300 (a lane's last pixels unlisted).
#define HMB_SHUTTER_LIST_CPU_GROUPS 256u

// list_shutter_rays: an 8 x 8 group per block of the moving tiles, or per run of blocks (above).
#define HMB_SHUTTER_LIST_BINDING_SURFACES 0  // uvec4 per pixel: the G-buffer's surfaces (velocity, object id)
#define HMB_SHUTTER_LIST_BINDING_TILE_MAX 1  // vec4 per tile: the gather's tile-max (velocity, speed)
#define HMB_SHUTTER_LIST_BINDING_TILES 2     // uint tile index per moving tile
#define HMB_SHUTTER_LIST_BINDING_COUNTERS 3  // ShutterRayCounters (cleared each frame)
#define HMB_SHUTTER_LIST_BINDING_LIST 4      // uint per listed pixel: shutterRayEntry(pixel index, rays)
#define HMB_SHUTTER_LIST_BINDING_SAMPLES 5    // uvec4 per pixel: the G-buffer's samples (colour)
#define HMB_SHUTTER_LIST_BINDING_MASK_COUNTERS 6  // RayMaskCounters: the moving tiles' count
#define HMB_SHUTTER_LIST_BINDING_PRIORITIES 7  // uint per list entry: its priority bucket (ranked lists only)
#define HMB_SHUTTER_LIST_BINDING_BUDGET 8      // ShutterRayBudget: the histogram grows here (ranked lists only)
#define HMB_SHUTTER_LIST_BINDING_COUNT 9
// The surfaces and samples are read as uniform texel buffers (counted in kernels/manifest.h).

// select_ray_budget: one invocation (a walk over HMB_RAY_BUDGET_BUCKETS counts), twice a frame:
// over the priority buckets (threshold, allowance), then over the ties' ranges (tieRange).
#define HMB_RAY_BUDGET_SELECT_BINDING_BUDGET 0  // ShutterRayBudget
#define HMB_RAY_BUDGET_SELECT_BINDING_COUNT 1

// tally_budget_ties and keep_budgeted_rays: one invocation per list entry, HMB_MASK_LIST_GROUP to
// a group, dispatched by the list's counters.
#define HMB_RAY_BUDGET_TALLY_BINDING_LIST 0        // list_shutter_rays' list
#define HMB_RAY_BUDGET_TALLY_BINDING_PRIORITIES 1  // its entries' priority buckets
#define HMB_RAY_BUDGET_TALLY_BINDING_COUNTERS 2    // ShutterRayCounters of the list
#define HMB_RAY_BUDGET_TALLY_BINDING_BUDGET 3      // ShutterRayBudget: the ties' histogram grows here
#define HMB_RAY_BUDGET_TALLY_BINDING_COUNT 4
#define HMB_RAY_BUDGET_KEEP_BINDING_LIST 0          // list_shutter_rays' list
#define HMB_RAY_BUDGET_KEEP_BINDING_PRIORITIES 1    // its entries' priority buckets
#define HMB_RAY_BUDGET_KEEP_BINDING_COUNTERS 2      // ShutterRayCounters of the list
#define HMB_RAY_BUDGET_KEEP_BINDING_BUDGET 3        // ShutterRayBudget (select_ray_budget's)
#define HMB_RAY_BUDGET_KEEP_BINDING_KEPT 4          // uint per kept entry, as the list's
#define HMB_RAY_BUDGET_KEEP_BINDING_KEPT_COUNTERS 5  // ShutterRayCounters of the kept list (cleared each frame)
#define HMB_RAY_BUDGET_KEEP_BINDING_COUNT 6

// trace_shutter_rays: one invocation per list entry, HMB_MASK_LIST_GROUP to a group.
#define HMB_SHUTTER_TRACE_BINDING_CAMERAS 0   // PinholeCamera per trace-scene time: the frame's, then each stratum's
#define HMB_SHUTTER_TRACE_BINDING_LIST 1      // list_shutter_rays' list
#define HMB_SHUTTER_TRACE_BINDING_COUNTERS 2  // ShutterRayCounters: the list's length; rays are counted into it
#define HMB_SHUTTER_TRACE_BINDING_OUTPUT 3    // vec4 per pixel: the frame's colour, overwritten at listed pixels
// The trace scene (trace/trace_scene_bindings.glsl), then the scene's shading buffers.
#define HMB_SHUTTER_TRACE_BINDING_TRACE_SCENE 4
#define HMB_SHUTTER_TRACE_BINDING_SCENE (HMB_SHUTTER_TRACE_BINDING_TRACE_SCENE + HMB_TRACE_SCENE_BINDINGS)
#define HMB_SHUTTER_TRACE_BINDING_COUNT (HMB_SHUTTER_TRACE_BINDING_SCENE + HMB_SCENE_BINDINGS)

// A listed pixel takes a ray per this many pixels of the fastest blur around it (at least 2,
// at most the strata): 1 px gained little over 2 px for many more rays, 4 px lost a little for a
// few fewer (bench/results/hybrid-kernel-shapes/).
#define HMB_SHUTTER_RAY_SPACING 2.0f
// A colour step along a path that lists the pixel too (an edge of a texture or of shading on
// one object sweeps over it as an object's edge does): a change of more than this in a channel
// of shutterRayColorKey. Smaller steps list more rays and gain more; this one sits between
// (bench/results/hybrid-kernel-shapes/).
#define HMB_SHUTTER_RAY_COLOR_STEP 0.1f
// The most shutter strata (and so rays per pixel) a frame can have.
#define HMB_MAX_SHUTTER_STRATA 16u
// A list entry: the pixel index in the low 28 bits, log2 of its rays in the high 4 (images are
// at most 16384 x 16384 pixels, 2^28: hmb::kMaxImageSide).
#define HMB_SHUTTER_ENTRY_PIXEL_BITS 28u
// A ray budget ranks the listed pixels in this many buckets of their priority, an eighth of an
// octave each (shutterRayPriorityBucket); bucket 0 holds the pixels expected to remove nothing.
// The threshold bucket's ties are split as many ways by pixel index.
#define HMB_RAY_BUDGET_BUCKETS 256u

HMB_GPU_BEGIN

struct MovingTilesParams {
  uint tileCount;
  uint pad0;
  uint pad1;
  uint pad2;
};

// Cleared each frame. count: list_shutter_rays' entries; the dispatch (a
// VkDispatchIndirectCommand) grows with the list, HMB_SHUTTER_RAY_GROUPS_PER_ROW groups to a row;
// rayCount: the rays trace_shutter_rays traced.
struct ShutterRayCounters {
  uint count;
  uint dispatchX;
  uint dispatchY;
  uint dispatchZ;
  uint rayCount;
  uint pad0;
  uint pad1;
  uint pad2;
};

struct ShutterRayListParams {
  GatherParams blur;  // the frame's blur: its velocities are read as the gathers read them
  uint strata;        // shutter strata of the frame (a power of two, at least 2)
  uint ranks;         // 1: walk each path whole and write its priority bucket (a ray budget is set)
  uint pad1;
  uint pad2;
};

// A ray budget's working state, written by the host each frame (the budget, the ranges) and
// cleared but for them. histogram: pairs of rays listed per priority bucket (every pixel takes
// an even number: pairs keep a 16384^2 image's sum within 32 bits). select_ray_budget writes
// the bucket where the budget runs out (threshold: the pixels above it are kept whole) and the
// pairs its own pixels may still take (allowance); tally_budget_ties counts that bucket's pairs
// per range of rangePixels pixel indices (ties), and select_ray_budget again the first range
// that no longer fits (tieRange: the threshold bucket's pixels below it are kept).
struct ShutterRayBudget {
  uint budgetPairs;
  uint rangePixels;
  uint threshold;
  uint allowance;
  uint tieRange;
  uint pad0;
  uint pad1;
  uint pad2;
  uint histogram[HMB_RAY_BUDGET_BUCKETS];
  uint ties[HMB_RAY_BUDGET_BUCKETS];
};

struct RayBudgetSelectParams {
  uint ties;  // 0: over the priority buckets, from the highest; 1: over the ties' ranges, from the lowest
  uint pad0;
  uint pad1;
  uint pad2;
};

struct ShutterRayTraceParams {
  uint width;
  uint height;
  uint instanceCount;
  uint timeCount;  // the trace scene's times: the frame's (index 0), then the strata's (1 + s)
  uint strata;
  float tMin;  // the near plane's depth
  float tMax;  // the far plane's depth
  uint pad0;
};

HMB_SHARED uint shutterRayEntry(uint pixelIndex, uint rays) {
  const uint log2Rays = rays >= 16u ? 4u : (rays >= 8u ? 3u : (rays >= 4u ? 2u : 1u));  // rays: 2, 4, 8 or 16
  return pixelIndex | (log2Rays << HMB_SHUTTER_ENTRY_PIXEL_BITS);
}
HMB_SHARED uint shutterRayEntryPixel(uint entry) { return entry & ((1u << HMB_SHUTTER_ENTRY_PIXEL_BITS) - 1u); }
HMB_SHARED uint shutterRayEntryRays(uint entry) { return 1u << (entry >> HMB_SHUTTER_ENTRY_PIXEL_BITS); }

// A colour as the colour-step test compares it: clamped to the display's range and square-rooted,
// near the display's own encoding, so a step means about as much in dark and light colours.
HMB_SHARED vec3 shutterRayColorKey(vec3 linear) { return sqrt(clamp(linear, vec3(0.0f), vec3(1.0f))); }
HMB_SHARED bool shutterRayColorsDiffer(vec3 keyA, vec3 keyB) {
  const vec3 d = abs(keyA - keyB);
  return max(d.x, max(d.y, d.z)) > HMB_SHUTTER_RAY_COLOR_STEP;
}

// The rays of a listed pixel whose neighbourhood blurs at most `fastestSpeed` pixels: one per
// HMB_SHUTTER_RAY_SPACING pixels, rounded up to a power of two, from 2 to the frame's strata.
HMB_SHARED uint shutterRaysFor(float fastestSpeed, uint strata) {
  uint rays = 2u;
  if (fastestSpeed > 2.0f * HMB_SHUTTER_RAY_SPACING) rays = 4u;
  if (fastestSpeed > 4.0f * HMB_SHUTTER_RAY_SPACING) rays = 8u;
  if (fastestSpeed > 8.0f * HMB_SHUTTER_RAY_SPACING) rays = 16u;
  return min(rays, strata);
}

// The error a listed pixel's rays are expected to remove, per ray: the contrast across the edge
// (the largest step of shutterRayColorKey's channels between the pixel and what its path meets),
// times the share of its path over something else (the share of the shutter the edge covers
// it), over its rays. differing of samples: the path's samples that meet something else.
HMB_SHARED float shutterRayPriority(float contrast, uint differing, uint samples, uint rays) {
  return contrast * (float(differing) / float(max(samples, 1u))) / float(max(rays, 1u));
}

// A priority's bucket: its float's exponent and top three mantissa bits (an eighth of an octave,
// exact on every device), from 1 for about 2^-32 and less to 255 for 1 and more; 0 for nothing.
HMB_SHARED uint shutterRayPriorityBucket(float priority) {
  if (!(priority > 0.0f)) return 0u;
  const uint eighths = floatBitsToUint(min(priority, 1.0f)) >> 20u;  // 8 * (exponent + 127) + 3 mantissa bits
  return uint(clamp(int(eighths) - int(127u * 8u - HMB_RAY_BUDGET_BUCKETS + 1u), 1, int(HMB_RAY_BUDGET_BUCKETS - 1u)));
}

// The range of pixel indices a tie in the threshold bucket is counted in (ShutterRayBudget).
HMB_SHARED uint rayBudgetTieRange(uint pixelIndex, uint rangePixels) {
  return min(pixelIndex / max(rangePixels, 1u), HMB_RAY_BUDGET_BUCKETS - 1u);
}

// A pixel's rays take every (strata / rays)-th stratum from this one on: neighbours start at
// different strata, so their few times do not line up into copies of an edge.
HMB_SHARED uint shutterRayFirstStratum(uint pixelIndex, uint rays, uint strata) {
  return mblurHash(pixelIndex, 0x5u, 0x9Bu) % (strata / rays);
}

HMB_GPU_END

#define HMB_SHUTTER_RAY_GROUPS_PER_ROW 65535u

HMB_CHECK_SIZE(ShutterRayCounters, 32)
HMB_CHECK_SIZE(ShutterRayListParams, 80)
HMB_CHECK_SIZE(ShutterRayTraceParams, 32)
HMB_CHECK_SIZE(MovingTilesParams, 16)
HMB_CHECK_SIZE(ShutterRayBudget, 32 + 8 * HMB_RAY_BUDGET_BUCKETS)
HMB_CHECK_SIZE(RayBudgetSelectParams, 16)

#endif
