// Plain C++ of the hybrid method's kernel math (kernels/ray_mask/ray_mask_common.glsl,
// edge_mask.comp, range_check.comp, size_list_dispatch.comp, mask_coverage.comp and the
// composites of kernels/reveal/composite.comp), operation for operation, so the kernels can be compared with it
// on any input. The motion blur functions they share come from tests/mblur/mblur_reference.h.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/hybrid_settings.h"
#include "hmblur/post_process_settings.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "runtime/passes/ray_mask_stage.h"
#include "tests/mblur/mblur_reference.h"

namespace hmb::test::hybrid {

// What the ray mask reads: the G-buffer's normal-depth, velocity and object id, row 0 at the top.
struct MaskLayer {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<glm::vec4> normalDepth;  // world normal, w camera-space depth
  std::vector<glm::vec2> velocity;     // pixels per frame
  std::vector<uint32_t> objectId;
  // Each pixel's path over the shutter (mblur::Layer::shutterPaths); empty: none. Read where
  // parameters.blur.flags has HMB_GATHER_FLAG_CURVED_PATH.
  std::vector<glm::uvec2> shutterPaths;
  // Linear RGB per pixel; empty: black. Read by the shutter rays' colour steps.
  std::vector<glm::vec3> color;
};

// The layer as the kernels read it: every pixel through the packed surface the device holds
// (kernels/shared/layer_layout.h): octahedral normals (0 where the object id is 0), non-finite
// velocities as none. The references below that take a MaskLayer read it through this.
MaskLayer stored(const MaskLayer& layer);

// ray_mask_common.glsl
bool endsOnDeeperObject(uint32_t idHere, float depthHere, uint32_t idEnd, float depthEnd, float softZExtent);
float sobelSmooth(int k);
float sobelDerivative(int k);
float normalizedEdge(float x);

// edge_mask.comp
glm::vec3 sanitizeNormal(glm::vec3 n);
// Eq. 3's x at pixel (x, y): delta_d + delta_n. depthHere: the pixel's sanitized depth.
float edgeStrength(const MaskLayer& layer, int x, int y, float depthHere);
// Eq. 4's x_n at every pixel (whether or not it moves).
std::vector<float> normalizedEdges(const MaskLayer& layer);
// The edge mask (0/1 per pixel).
std::vector<uint32_t> edgeMask(const MaskLayer& layer, const passes::RayMaskParameters& parameters);
// Per pixel: true where eqs. 1 and 2 hold (the pixel moves and its end lies on a deeper object),
// that is, where the edge mask is decided by x_n > e.
std::vector<bool> edgeCandidates(const MaskLayer& layer, const passes::RayMaskParameters& parameters);

// The list entry (gpu::rangeBlockEntry) of the 8 x 8 block at (ox, oy) in a tile of side
// tileSize: its first pixel, and whether it is the tile's last block across and down.
uint32_t rangeBlockEntryOf(uint32_t ox, uint32_t oy, uint32_t tileSize);

// list_range_blocks.comp: the entry (rangeBlockEntryOf) of each 8 x 8 block the range check
// walks, ascending: the blocks of the moving tiles (the gather's tile-max at parameters.blur.tileSize)
// with a pixel of the edge mask `edges` (one per pixel) within ceil(tile-max speed) + 1 pixels'
// coarse blocks (edge_mask's, a pixel of margin), or whose tile's speed was clamped, or along
// curved paths.
std::vector<uint32_t> rangeBlocks(const MaskLayer& layer, const std::vector<uint32_t>& edges,
                                  const passes::RayMaskParameters& parameters);

// range_check.comp: the ray mask (0/1 per pixel) from the velocities and an edge mask.
std::vector<uint32_t> rangeCheck(const std::vector<glm::vec2>& velocity, const std::vector<uint32_t>& edges,
                                 uint32_t width, uint32_t height, const passes::RayMaskParameters& parameters);
// The same along curved paths (HMB_GATHER_FLAG_CURVED_PATH in parameters.blur.flags): each
// pixel with a path walks its own (mblur_common.glsl's inversePath), the others go straight.
std::vector<uint32_t> rangeCheck(const MaskLayer& layer, const std::vector<uint32_t>& edges,
                                 const passes::RayMaskParameters& parameters);

// range_check.comp and mask_coverage.comp with HMB_RANGE_CHECK_LIST_UNCOVERED: true for the mask pixels whose coverage
// composite samples (parameters.blur.samples, jitter from parameters.blur.seed, along the
// displacement clamped to parameters.blur.maxSpeed) meet another object deeper than the pixel.
std::vector<bool> revealedPixels(const MaskLayer& layer, const std::vector<uint32_t>& mask,
                                 const passes::RayMaskParameters& parameters);

// list_shutter_rays.comp: the rays each pixel takes over the shutter (0: not listed), for a
// frame of `strata` strata, from the gather's tile-max at parameters.blur.tileSize and the
// layer's object ids and colours. Only pixels of tiles whose fastest pixel moves
// kMinBlurPixels or more (list_moving_tiles) are listed.
// priorities: when given, each listed pixel's priority bucket as a ray budget ranks it
// (shutterRayPriorityBucket), 0 elsewhere.
std::vector<uint32_t> shutterRays(const MaskLayer& layer, const passes::RayMaskParameters& parameters, uint32_t strata,
                                  std::vector<uint32_t>* priorities = nullptr);

// select_ray_budget, tally_budget_ties and keep_budgeted_rays: which listed pixels a budget of
// `budgetRays` keeps, given each pixel's rays and priority bucket (0 rays: not listed).
std::vector<bool> keptByBudget(const std::vector<uint32_t>& rays, const std::vector<uint32_t>& priorities,
                               uint32_t budgetRays);

// size_list_dispatch.comp: the counters after it ran on a mask of `maskCount` pixels (rayCount 0).
gpu::RayMaskCounters dispatchFor(uint32_t maskCount);
// The same with `unrevealed` more mask pixels at the list's back: maskPixels over both, and
// the coverage composite's dispatch over the back.
gpu::RayMaskCounters dispatchFor(uint32_t maskCount, uint32_t unrevealed);
// The counters as the range check leaves them for mask_coverage with `maskPixels` mask pixels
// (its dispatch sized), and the dispatches over the list's front and back each sized for them
// all: maskCount and unrevealedCount 0, for list_mask_blocks to count.
gpu::RayMaskCounters coverageDispatchFor(uint32_t maskPixels);

// mask_coverage.comp at each pixel where `mask` is not 0 (the others zero): the coverage
// composite's foreground F (the mean colour of the pixel and its samples on its object), alpha
// (the samples' share on it), and whether a sample lies behind the pixel (the pixel is listed
// for the reveal).
struct MaskCoverage {
  glm::vec3 foreground{0.0f};
  float alpha = 0.0f;
  bool meetsBackground = false;
};
std::vector<MaskCoverage> maskCoverage(const mblur::Layer& layer, const std::vector<uint32_t>& mask,
                                       const std::vector<uint32_t>& objectId,
                                       const passes::PostProcessSettings& settings);

// The hybrid's image: reveal/composite.comp at mask pixels with the background, the object ids
// and the form, over the post-process gather (mblur/gather.comp) everywhere else.
std::vector<glm::vec4> compositeGather(const mblur::Layer& layer, const std::vector<glm::vec4>& neighborMax,
                                       const std::vector<uint32_t>& mask, const std::vector<glm::vec4>& background,
                                       const std::vector<uint32_t>& objectId,
                                       const passes::PostProcessSettings& settings, passes::HybridComposite composite,
                                       passes::MaskWeights maskWeights);

}  // namespace hmb::test::hybrid
