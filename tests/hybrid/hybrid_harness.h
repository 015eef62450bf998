// Runs the hybrid method's passes on the test device on host data and reads the results back:
// the ray mask (RayMaskStage), the gather with the composite and in pixel-list mode
// (GatherPass), and the ray reveal (RevealPass) of a scene's G-buffer.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/hybrid_settings.h"
#include "hmblur/post_process_settings.h"
#include "hmblur/scene.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/ray_mask_stage.h"
#include "tests/hybrid/hybrid_reference.h"
#include "tests/mblur/mblur_reference.h"
#include "tests/support/layer_readback.h"

namespace hmb::vk {
class Context;
}

namespace hmb::test::hybrid {

struct RayMaskReadback {
  std::vector<uint32_t> edges;  // per pixel
  std::vector<uint32_t> mask;        // per pixel: 1 in the ray mask, else 0
  std::vector<uint32_t> maskValues;  // per pixel as the device wrote it (HMB_MASK_*)
  std::vector<uint32_t> list;   // the list's first counters.maskCount entries
  std::vector<uint32_t> unrevealedList;  // its last counters.unrevealedCount entries
  std::vector<uint32_t> candidates;  // the edge candidates' first counters.candidateCount entries
  std::vector<uint32_t> rangeBlocks;  // list_range_blocks' first counters.rangeBlockCount entries
  std::vector<uint32_t> coverageList;  // with listOnlyUncovered: its first counters.coverageCount entries
  std::vector<glm::vec4> tileMax;     // the tile-max the mask started from (vec4 per tile)
  std::vector<uint32_t> movingTiles;  // the moving tiles' first counters.tileCount entries
  gpu::RayMaskCounters counters{};
};

// RayMaskStage on `layer` (edge mask, range check, compaction, dispatch size).
RayMaskReadback runRayMask(vk::Context& context, const MaskLayer& layer, const passes::RayMaskParameters& parameters);

// ShutterRaysPass's list (list_shutter_rays) of `layer` at `strata`, after the ray mask's
// moving tiles (RayMaskStage): the rays per pixel the list holds (0 where it lists none; a
// pixel listed twice fails the test), its counters and the ray mask's (the list's dispatch).
// groupsWanted: ShutterRaysPass::recordList's. rayBudget: when not 0, the list ranks its pixels
// and the budget's pass (select_ray_budget, keep_budgeted_rays) runs after it.
struct ShutterRayListReadback {
  std::vector<uint32_t> rays;
  gpu::ShutterRayCounters counters{};
  gpu::RayMaskCounters maskCounters{};
  // Under a budget: each listed pixel's priority bucket, the pixels kept, the budget's state and
  // the kept list's counters.
  std::vector<uint32_t> priorities;
  std::vector<bool> kept;
  gpu::ShutterRayBudget budget{};
  gpu::ShutterRayCounters keptCounters{};
};
ShutterRayListReadback runShutterRayList(vk::Context& context, const MaskLayer& layer,
                                         const passes::RayMaskParameters& parameters, uint32_t strata,
                                         std::optional<uint32_t> groupsWanted = std::nullopt, uint32_t rayBudget = 0);

// One gather of `layer`: the composite (CompositePass, after MaskCoveragePass over the mask's
// pixels for the coverage form) with `background`, which needs the mask and the object ids;
// else with `list`, the background gather (BackgroundGatherPass) of the listed pixels, its
// dispatch sized on the host as size_list_dispatch sizes it, reading
// `revealed` (default: `layer` itself) where the mask is HMB_MASK_REVEALED; else the
// post-process gather (GatherPass), outside the mask alone when there is one. The output
// buffer starts as `sentinel` everywhere.
struct GatherRun {
  const std::vector<uint32_t>* mask = nullptr;
  const std::vector<glm::vec4>* background = nullptr;
  const std::vector<uint32_t>* objectId = nullptr;
  passes::HybridComposite composite = passes::HybridComposite::Coverage;
  const std::vector<uint32_t>* list = nullptr;
  const mblur::Layer* revealed = nullptr;
  passes::MaskWeights maskWeights;  // the composite's and the background gather's
  glm::vec4 sentinel{0.0f};
  // The coverage composite's: mask_coverage's output (vec4 per pixel, NaN where unwritten) and
  // the mask's values after it, read back here when set.
  std::vector<glm::vec4>* coverageOut = nullptr;
  std::vector<uint32_t>* maskOut = nullptr;
  // The list's front (for the reveal) and back (read from its end inwards) after list_mask_blocks.
  std::vector<uint32_t>* frontOut = nullptr;
  std::vector<uint32_t>* backOut = nullptr;
};
std::vector<glm::vec4> runGather(vk::Context& context, const mblur::Layer& layer,
                                 const std::vector<glm::vec4>& neighborMax, const GatherRun& run,
                                 const passes::PostProcessSettings& settings);

// One G-buffer layer as read back.
using GLayer = LayerReadback;

// The G-buffer of `scene` at `frameTime`, and the ray reveal of the listed pixels written into
// buffers that start as the sentinels everywhere.
struct RevealReadback {
  FrameCamera camera;
  GLayer raster;
  GLayer revealed;
  gpu::RayMaskCounters counters{};
};
// What the reveal's output layer holds before it runs (packed by runReveal), read back: a pixel
// the reveal did not write keeps it.
inline constexpr glm::vec4 kSentinelColor{7.0f, 7.0f, 7.0f, 1.0f};
inline constexpr float kSentinelDepth = -7.0f;
inline constexpr glm::vec2 kSentinelVelocity{-7.0f, -7.0f};
inline constexpr uint32_t kSentinelId = 0xDEADBEEFu;
// editRaster, when given, changes the G-buffer (read back and written again) before the reveal
// reads it; RevealReadback::raster is the G-buffer as the reveal read it.
RevealReadback runReveal(vk::Context& context, const scene::Scene& scene, float frameTime, uint32_t width,
                         uint32_t height, const std::vector<uint32_t>& list, const passes::HybridSettings& settings,
                         const std::function<void(passes::LayerContents&)>& editRaster = {});

// Random mask inputs: a few rectangles (objects with their own id, depth, normal and motion)
// over a background object with noisy depth and normals, some pixels of it moving too.
MaskLayer randomMaskLayer(uint32_t width, uint32_t height, std::mt19937& rng);

// A random mask layer with a share of its pixels replaced by values a G-buffer should never
// hold (NaN and infinite velocities, depths and normals, huge and negative ones) and some it
// may (zero and sub-pixel motion, the background's id 0).
MaskLayer adversarialMaskLayer(uint32_t width, uint32_t height, std::mt19937& rng);

// Object 2 (depth 1) moving by `velocity` over all but the last `stillColumns` columns, where a
// still, deeper object 3 (depth 5) is: long walks with an edge at their end.
MaskLayer movingOntoStillColumns(uint32_t width, uint32_t height, uint32_t stillColumns, glm::vec2 velocity);

}  // namespace hmb::test::hybrid
