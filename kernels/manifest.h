// Every embedded kernel in one table: its name (its file under kernels/ without ".comp"), its
// traits, how many binding numbers its layout header declares, its push-constant block, and how
// many of its bindings its plain build reads as uniform texel buffers. The passes build their
// kernels from it (vk::ComputeKernel takes an entry), the pipeline tests check every kernel's
// SPIR-V against it, and CMake reads the kernels that also get an address build from it
// (kernels/CMakeLists.txt): a new kernel is its .comp, its layout header and one line here.
#pragma once

#include <cstdint>
#include <string_view>

#include "kernels/bvh/bvh_build_layout.h"
#include "kernels/bvh/linear_bvh_layout.h"
#include "kernels/bvh/treelet_build_layout.h"
#include "kernels/debug/floor_pass.h"
#include "kernels/debug/pack_layer.h"
#include "kernels/debug/test_pattern.h"
#include "kernels/deform/deform_layout.h"
#include "kernels/engine/engine_layout.h"
#include "kernels/gbuffer/gbuffer_layout.h"
#include "kernels/mblur/mblur_layout.h"
#include "kernels/output/encode_display.h"
#include "kernels/raster/raster_layout.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/reference/reference_layout.h"
#include "kernels/reveal/reveal_layout.h"
#include "kernels/shared/scene_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "kernels/trace/trace_layout.h"

namespace hmb::kernels {

enum KernelTraits : uint32_t {
  kPlain = 0,
  // Also built to bind each group of buffers as a table of device addresses
  // (kernels/shared/*_bindings.glsl), for devices with few storage-buffer bindings.
  kAddressBuild = 1u << 0,
  kInt64Atomics = 1u << 1,  // builds only where the device has 64-bit buffer atomics
  kShades = 1u << 2,        // includes shared/shading.glsl: also built without the texture path
};

struct KernelFacts {
  std::string_view name;
  uint32_t traits;         // KernelTraits
  uint32_t bindings;       // the binding numbers its layout header declares (*_BINDING_COUNT)
  uint32_t pushBytes;      // its push-constant block
  uint32_t texelBindings;  // of `bindings`, those its plain build reads as uniform texel buffers
  uint32_t imageBindings = 0;  // of `bindings`, an engine's images (sampled or storage)

  constexpr bool has(KernelTraits trait) const { return (traits & trait) != 0; }
  constexpr uint32_t storageBindings() const { return bindings - texelBindings - imageBindings; }
};

// What a kernel that traces and shades reads through texel views: the trace scene's and the
// shading scene's records.
inline constexpr uint32_t kTracedSceneTexels = HMB_TRACE_SCENE_TEXEL_BUFFERS + HMB_SCENE_TEXEL_BUFFERS;

// One line a kernel, sorted by name; a kernel's name and traits share its first line (CMake
// reads them there).
// clang-format off
inline constexpr KernelFacts kManifest[] = {
    {"bvh/begin_build", kPlain, HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), 1},
    {"bvh/build_level", kPlain, HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), 1},
    {"bvh/build_small_tasks", kPlain, HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), 1},
    {"bvh/deformed_leaf_triangles", kPlain, HMB_DEFORMED_LEAVES_BINDING_COUNT, sizeof(glm::uvec2), 0},
    {"bvh/insert_primitives", kPlain, HMB_INSERT_BINDING_COUNT, sizeof(gpu::BvhBuildParams), 1},
    {"bvh/linear_bounds", kPlain, HMB_LINEAR_BOUNDS_BINDING_COUNT, sizeof(gpu::LinearBvhParams), 0},
    {"bvh/linear_hierarchy", kPlain, HMB_LINEAR_HIERARCHY_BINDING_COUNT, sizeof(gpu::LinearBvhParams), 0},
    {"bvh/linear_pack", kPlain, HMB_LINEAR_PACK_BINDING_COUNT, sizeof(gpu::LinearBvhParams), 0},
    {"bvh/linear_sort_keys", kPlain, HMB_LINEAR_SORT_BINDING_COUNT, sizeof(gpu::LinearBvhParams), 0},
    {"bvh/pack_deferred_nodes", kPlain, HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), 1},
    {"bvh/refit_bounds", kPlain, HMB_REFIT_BOUNDS_BINDINGS, sizeof(gpu::BvhRefitParams), 0},
    {"bvh/refit_pack", kPlain, HMB_REFIT_PACK_BINDINGS, sizeof(gpu::BvhRefitParams), 0},
    {"bvh/refit_parents", kPlain, HMB_REFIT_PARENTS_BINDINGS, sizeof(gpu::BvhRefitParams), 0},
    {"bvh/refit_places", kPlain, HMB_REFIT_PLACES_BINDINGS, sizeof(gpu::BvhRefitParams), 0},
    {"bvh/size_build_dispatch", kPlain, HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), 1},
    {"bvh/treelet_centroid_bounds", kPlain, HMB_TREELET_BOUNDS_BINDINGS, sizeof(gpu::TreeletBuildParams), 0},
    {"bvh/treelet_hierarchy", kPlain, HMB_TREELET_HIERARCHY_BINDINGS, sizeof(gpu::TreeletBuildParams), 0},
    {"bvh/treelet_morton_codes", kPlain, HMB_TREELET_CODES_BINDINGS, sizeof(gpu::TreeletBuildParams), 0},
    {"bvh/treelet_optimize", kPlain, HMB_TREELET_OPTIMIZE_BINDINGS, sizeof(gpu::TreeletBuildParams), 0},
    {"bvh/treelet_pack", kPlain, HMB_TREELET_PACK_BINDINGS, sizeof(gpu::TreeletBuildParams), 0},
    {"bvh/treelet_sort_pass", kPlain, HMB_TREELET_SORT_BINDINGS, sizeof(gpu::TreeletBuildParams), 0},
    {"bvh/triangle_bounds", kPlain, HMB_TRIANGLE_BOUNDS_BINDING_COUNT, sizeof(uint32_t), 0},
    {"debug/floor_pass", kPlain, HMB_FLOOR_BINDING_COUNT, sizeof(gpu::FloorParams), 0},
    {"debug/pack_layer", kPlain, HMB_PACK_LAYER_BINDING_COUNT, sizeof(gpu::PackLayerParams), 0},
    {"debug/test_pattern", kPlain, HMB_TEST_PATTERN_BINDING_COUNT, sizeof(gpu::TestPatternParams), 0},
    {"deform/deform_vertices", kPlain, HMB_DEFORM_BINDING_COUNT, sizeof(gpu::DeformParams), 0},
    {"engine/pack_engine_colour_images", kPlain, HMB_ENGINE_COLOUR_IMAGES_BINDING_COUNT, sizeof(gpu::EngineGBufferParams), 0, 3},
    {"engine/pack_engine_gbuffer", kPlain, HMB_ENGINE_BINDING_COUNT, sizeof(gpu::EngineGBufferParams), 0},
    {"engine/pack_engine_images", kPlain, HMB_ENGINE_BINDING_COUNT, sizeof(gpu::EngineGBufferParams), 0, 5},
    {"engine/write_output_rgba16f", kPlain, HMB_ENGINE_OUTPUT_BINDING_COUNT, sizeof(gpu::EngineOutputParams), 0, 1},
    {"engine/write_output_rgba32f", kPlain, HMB_ENGINE_OUTPUT_BINDING_COUNT, sizeof(gpu::EngineOutputParams), 0, 1},
    {"gbuffer/resolve_gbuffer", kShades | kAddressBuild, HMB_RESOLVE_BINDING_COUNT, sizeof(gpu::ResolveParams),
     5 + HMB_SCENE_TEXEL_BUFFERS},
    {"gbuffer/resolve_shutter_path", kPlain, HMB_SHUTTER_PATH_RESOLVE_BINDING_COUNT, sizeof(gpu::ResolveParams), 5},
    {"mblur/copy_still_blocks", kPlain, HMB_STILL_BLOCKS_BINDING_COUNT, sizeof(gpu::StillBlocksParams), 1},
    {"mblur/gather", kPlain, HMB_GATHER_BINDING_COUNT, sizeof(gpu::GatherParams), 3},
    {"mblur/gather_jimenez", kPlain, HMB_FILTER_BINDING_COUNT, sizeof(gpu::JimenezParams), 3},
    {"mblur/list_gather_blocks", kPlain, HMB_GATHER_BLOCKS_BINDING_COUNT, sizeof(gpu::GatherBlocksParams), 0},
    {"mblur/neighbor_max", kPlain, HMB_NEIGHBOR_MAX_BINDING_COUNT, sizeof(gpu::NeighborMaxParams), 0},
    {"mblur/tile_max", kPlain, HMB_TILE_MAX_BINDING_COUNT, sizeof(gpu::TileMaxParams), 1},
    {"output/encode_display", kPlain, HMB_ENCODE_DISPLAY_BINDING_COUNT, sizeof(gpu::EncodeDisplayParams), 0},
    {"raster/bin_large_triangles", kPlain, HMB_BIN_LARGE_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/clip_triangles", kPlain, HMB_SETUP_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/link_tile_pairs", kPlain, HMB_LINK_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/rasterize_tile_lists", kPlain, HMB_TILE_LISTS_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/rasterize_tiles", kInt64Atomics, HMB_RASTERIZE_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/rasterize_tiles_depth32", kPlain, HMB_RASTERIZE_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/setup_triangles", kPlain, HMB_SETUP_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/size_dispatch", kPlain, HMB_SIZE_DISPATCH_BINDING_COUNT, sizeof(gpu::RasterParams), 0},
    {"raster/transform_shutter_path", kPlain, HMB_SHUTTER_PATH_BINDING_COUNT, sizeof(gpu::ShutterPathParams), 0},
    {"raster/transform_vertices", kPlain, HMB_TRANSFORM_BINDING_COUNT, sizeof(uint32_t), 0},
    {"ray_mask/edge_mask", kPlain, HMB_EDGE_MASK_BINDING_COUNT, sizeof(gpu::RayMaskParams), 1},
    {"ray_mask/list_mask_blocks", kPlain, HMB_LIST_MASK_BLOCKS_BINDING_COUNT, sizeof(gpu::RayMaskParams), 1},
    {"ray_mask/list_range_blocks", kPlain, HMB_RANGE_BLOCKS_BINDING_COUNT, sizeof(gpu::RayMaskParams), 0},
    {"ray_mask/list_range_mask", kPlain, HMB_RANGE_MASK_LIST_BINDING_COUNT, sizeof(gpu::RayMaskParams), 0},
    {"ray_mask/mask_coverage", kPlain, HMB_MASK_COVERAGE_BINDING_COUNT, sizeof(gpu::RayMaskParams), 3},
    {"ray_mask/range_check", kPlain, HMB_RANGE_CHECK_BINDING_COUNT, sizeof(gpu::RayMaskParams), 2},
    {"ray_mask/size_list_dispatch", kPlain, HMB_SIZE_LIST_BINDING_COUNT, sizeof(gpu::SizeListParams), 0},
    {"ray_mask/tile_max_edge_candidates", kPlain, HMB_TILE_MAX_CANDIDATES_BINDING_COUNT, sizeof(gpu::RayMaskParams), 2},
    {"reference/accumulate_sample", kShades | kAddressBuild, HMB_REFERENCE_BINDING_COUNT,
     sizeof(gpu::ReferenceSampleParams), kTracedSceneTexels},
    {"reference/average_samples", kPlain, HMB_AVERAGE_BINDING_COUNT, sizeof(gpu::AverageParams), 0},
    {"reference/fold_sums", kPlain, HMB_FOLD_SUMS_BINDING_COUNT, sizeof(gpu::FoldSumsParams), 0},
    {"reference/find_moving_pixels", kPlain, HMB_MOVING_PIXELS_BINDING_COUNT, sizeof(gpu::MovingPixelsParams), 0},
    {"reveal/composite", kPlain, HMB_COMPOSITE_BINDING_COUNT, sizeof(gpu::GatherParams), 6},
    {"reveal/gather_background", kAddressBuild, HMB_BACKGROUND_GATHER_BINDING_COUNT, sizeof(gpu::GatherParams), 6},
    {"reveal/reveal_background", kShades | kAddressBuild, HMB_REVEAL_BINDING_COUNT, sizeof(gpu::RevealParams),
     HMB_LAYER_BINDINGS + kTracedSceneTexels},
    {"shutter_rays/list_moving_tiles", kPlain, HMB_MOVING_TILES_BINDING_COUNT, sizeof(gpu::MovingTilesParams), 0},
    {"shutter_rays/keep_budgeted_rays", kPlain, HMB_RAY_BUDGET_KEEP_BINDING_COUNT, 0, 0},
    {"shutter_rays/list_shutter_rays", kPlain, HMB_SHUTTER_LIST_BINDING_COUNT, sizeof(gpu::ShutterRayListParams), 2},
    {"shutter_rays/select_ray_budget", kPlain, HMB_RAY_BUDGET_SELECT_BINDING_COUNT, sizeof(gpu::RayBudgetSelectParams),
     0},
    {"shutter_rays/tally_budget_ties", kPlain, HMB_RAY_BUDGET_TALLY_BINDING_COUNT, 0, 0},
    {"shutter_rays/trace_shutter_rays", kShades | kAddressBuild, HMB_SHUTTER_TRACE_BINDING_COUNT,
     sizeof(gpu::ShutterRayTraceParams), kTracedSceneTexels},
    {"trace/instance_motion_bounds", kPlain, HMB_MOTION_BOUNDS_BINDING_COUNT, sizeof(gpu::TraceParams), 0},
    {"trace/trace_rays", kAddressBuild, HMB_TRACE_BINDING_COUNT, sizeof(gpu::TraceParams),
     HMB_TRACE_SCENE_TEXEL_BUFFERS},
};
// clang-format on

// The entry of kernel `name`, or null.
constexpr const KernelFacts* findKernelFacts(std::string_view name) {
  for (const KernelFacts& kernel : kManifest)
    if (kernel.name == name) return &kernel;
  return nullptr;
}

// The entry of kernel `name`, found while compiling: a name missing from the table does not compile.
consteval const KernelFacts& kernel(std::string_view name) {
  const KernelFacts* found = findKernelFacts(name);
  if (!found) throw "no such kernel in kernels/manifest.h";
  return *found;
}

}  // namespace hmb::kernels
