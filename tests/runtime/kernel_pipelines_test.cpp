// Every embedded kernel builds a compute pipeline against the layout its shared header
// declares; the validation layer checks the SPIR-V's bindings and push constants against it.
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <string_view>

#include "kernels/bvh/bvh_build_layout.h"
#include "kernels/bvh/linear_bvh_layout.h"
#include "kernels/bvh/treelet_build_layout.h"
#include "kernels/debug/floor_pass.h"
#include "kernels/debug/pack_layer.h"
#include "kernels/debug/test_pattern.h"
#include "kernels/gbuffer/gbuffer_layout.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/reveal/reveal_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "kernels/mblur/mblur_layout.h"
#include "kernels/output/encode_display.h"
#include "kernels/raster/raster_layout.h"
#include "kernels/reference/reference_layout.h"
#include "kernels/deform/deform_layout.h"
#include "kernels/engine/engine_layout.h"
#include "kernels/shared/scene_layout.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"
#include "runtime/vulkan/kernel_interface.h"
#include "runtime/vulkan/kernel_registry.h"
#include "runtime/vulkan/kernel_variants.h"
#include "tests/support/expect_error.h"
#include "tests/support/spirv_modes.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

struct KernelLayout {
  const char* name;
  uint32_t bindings;
  uint32_t pushBytes;
  bool needsInt64Atomics;
  bool shades = false;  // includes shared/shading.glsl: also built without the texture path
  uint32_t texelBindings = 0;  // of `bindings`, those read as uniform texel buffers (plain build)
  uint32_t storageBindings() const { return bindings - texelBindings; }
};

const KernelLayout kLayouts[] = {
    {"bvh/triangle_bounds", HMB_TRIANGLE_BOUNDS_BINDING_COUNT, sizeof(uint32_t), false},
    {"bvh/deformed_leaf_triangles", HMB_DEFORMED_LEAVES_BINDING_COUNT, sizeof(glm::uvec2), false},
    {"deform/deform_vertices", HMB_DEFORM_BINDING_COUNT, sizeof(gpu::DeformParams), false},
    {"bvh/begin_build", HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), false, false, HMB_BUILD_TEXEL_BUFFERS},
    {"bvh/build_level", HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), false, false, HMB_BUILD_TEXEL_BUFFERS},
    {"bvh/size_build_dispatch", HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), false, false, HMB_BUILD_TEXEL_BUFFERS},
    {"bvh/build_small_tasks", HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), false, false, HMB_BUILD_TEXEL_BUFFERS},
    {"bvh/pack_deferred_nodes", HMB_BUILD_BINDING_COUNT, sizeof(gpu::BvhBuildParams), false, false, HMB_BUILD_TEXEL_BUFFERS},
    {"bvh/insert_primitives", HMB_INSERT_BINDING_COUNT, sizeof(gpu::BvhBuildParams), false, false, HMB_BUILD_TEXEL_BUFFERS},
    {"bvh/linear_sort_keys", HMB_LINEAR_SORT_BINDING_COUNT, sizeof(gpu::LinearBvhParams), false},
    {"bvh/linear_hierarchy", HMB_LINEAR_HIERARCHY_BINDING_COUNT, sizeof(gpu::LinearBvhParams), false},
    {"bvh/linear_bounds", HMB_LINEAR_BOUNDS_BINDING_COUNT, sizeof(gpu::LinearBvhParams), false},
    {"bvh/linear_pack", HMB_LINEAR_PACK_BINDING_COUNT, sizeof(gpu::LinearBvhParams), false},
    {"bvh/treelet_centroid_bounds", HMB_TREELET_BOUNDS_BINDINGS, sizeof(gpu::TreeletBuildParams), false},
    {"bvh/treelet_morton_codes", HMB_TREELET_CODES_BINDINGS, sizeof(gpu::TreeletBuildParams), false},
    {"bvh/treelet_sort_pass", HMB_TREELET_SORT_BINDINGS, sizeof(gpu::TreeletBuildParams), false},
    {"bvh/treelet_hierarchy", HMB_TREELET_HIERARCHY_BINDINGS, sizeof(gpu::TreeletBuildParams), false},
    {"bvh/treelet_optimize", HMB_TREELET_OPTIMIZE_BINDINGS, sizeof(gpu::TreeletBuildParams), false},
    {"bvh/treelet_pack", HMB_TREELET_PACK_BINDINGS, sizeof(gpu::TreeletBuildParams), false},
    {"bvh/refit_parents", HMB_REFIT_PARENTS_BINDINGS, sizeof(gpu::BvhRefitParams), false},
    {"bvh/refit_places", HMB_REFIT_PLACES_BINDINGS, sizeof(gpu::BvhRefitParams), false},
    {"bvh/refit_bounds", HMB_REFIT_BOUNDS_BINDINGS, sizeof(gpu::BvhRefitParams), false},
    {"bvh/refit_pack", HMB_REFIT_PACK_BINDINGS, sizeof(gpu::BvhRefitParams), false},
    {"trace/instance_motion_bounds", HMB_MOTION_BOUNDS_BINDING_COUNT, sizeof(gpu::TraceParams), false},
    {"trace/trace_rays", HMB_TRACE_BINDING_COUNT, sizeof(gpu::TraceParams), false, false,
     HMB_TRACE_SCENE_TEXEL_BUFFERS},
    {"debug/floor_pass", HMB_FLOOR_BINDING_COUNT, sizeof(gpu::FloorParams), false},
    {"debug/pack_layer", HMB_PACK_LAYER_BINDING_COUNT, sizeof(gpu::PackLayerParams), false},
    {"debug/test_pattern", HMB_TEST_PATTERN_BINDING_COUNT, sizeof(gpu::TestPatternParams), false},
    {"output/encode_display", HMB_ENCODE_DISPLAY_BINDING_COUNT, sizeof(gpu::EncodeDisplayParams), false},
    {"raster/transform_vertices", HMB_TRANSFORM_BINDING_COUNT, sizeof(uint32_t), false},
    {"raster/transform_shutter_path", HMB_SHUTTER_PATH_BINDING_COUNT, sizeof(gpu::ShutterPathParams), false},
    {"raster/setup_triangles", HMB_SETUP_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"raster/clip_triangles", HMB_SETUP_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"raster/size_dispatch", HMB_SIZE_DISPATCH_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"raster/bin_large_triangles", HMB_BIN_LARGE_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"raster/rasterize_tiles", HMB_RASTERIZE_BINDING_COUNT, sizeof(gpu::RasterParams), true},
    {"raster/rasterize_tiles_depth32", HMB_RASTERIZE_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"engine/pack_engine_gbuffer", HMB_ENGINE_BINDING_COUNT, sizeof(gpu::EngineGBufferParams), false},
    {"raster/link_tile_pairs", HMB_LINK_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"raster/rasterize_tile_lists", HMB_TILE_LISTS_BINDING_COUNT, sizeof(gpu::RasterParams), false},
    {"gbuffer/resolve_gbuffer", HMB_RESOLVE_BINDING_COUNT, sizeof(gpu::ResolveParams), false, true,
     HMB_RESOLVE_TEXEL_BUFFERS},
    {"gbuffer/resolve_shutter_path", HMB_SHUTTER_PATH_RESOLVE_BINDING_COUNT, sizeof(gpu::ResolveParams), false, false,
     5},
    {"reference/accumulate_sample", HMB_REFERENCE_BINDING_COUNT, sizeof(gpu::ReferenceSampleParams), false, true,
     HMB_TRACE_SCENE_TEXEL_BUFFERS + HMB_SCENE_TEXEL_BUFFERS},
    {"reference/average_samples", HMB_AVERAGE_BINDING_COUNT, sizeof(gpu::AverageParams), false},
    {"reference/find_moving_pixels", HMB_MOVING_PIXELS_BINDING_COUNT, sizeof(gpu::MovingPixelsParams), false},
    {"mblur/tile_max", HMB_TILE_MAX_BINDING_COUNT, sizeof(gpu::TileMaxParams), false, false, HMB_TILE_MAX_TEXEL_BUFFERS},
    {"mblur/neighbor_max", HMB_NEIGHBOR_MAX_BINDING_COUNT, sizeof(gpu::NeighborMaxParams), false},
    {"mblur/gather", HMB_GATHER_BINDING_COUNT, sizeof(gpu::GatherParams), false, false, HMB_FILTER_TEXEL_BUFFERS},
    {"mblur/list_gather_blocks", HMB_GATHER_BLOCKS_BINDING_COUNT, sizeof(gpu::GatherBlocksParams), false},
    {"mblur/copy_still_blocks", HMB_STILL_BLOCKS_BINDING_COUNT, sizeof(gpu::StillBlocksParams), false, false, 1},
    {"mblur/gather_jimenez", HMB_FILTER_BINDING_COUNT, sizeof(gpu::JimenezParams), false, false,
     HMB_FILTER_TEXEL_BUFFERS},
    {"reveal/composite", HMB_COMPOSITE_BINDING_COUNT, sizeof(gpu::GatherParams), false, false,
     HMB_COMPOSITE_TEXEL_BUFFERS},
    {"reveal/gather_background", HMB_BACKGROUND_GATHER_BINDING_COUNT, sizeof(gpu::GatherParams), false, false,
     HMB_BACKGROUND_GATHER_TEXEL_BUFFERS},
    {"ray_mask/tile_max_edge_candidates", HMB_TILE_MAX_CANDIDATES_BINDING_COUNT, sizeof(gpu::RayMaskParams), false, false,
     HMB_TILE_MAX_CANDIDATES_TEXEL_BUFFERS},
    {"ray_mask/edge_mask", HMB_EDGE_MASK_BINDING_COUNT, sizeof(gpu::RayMaskParams), false, false, HMB_EDGE_MASK_TEXEL_BUFFERS},
    {"ray_mask/range_check", HMB_RANGE_CHECK_BINDING_COUNT, sizeof(gpu::RayMaskParams), false, false,
     HMB_RANGE_CHECK_TEXEL_BUFFERS},
    {"ray_mask/list_range_mask", HMB_RANGE_MASK_LIST_BINDING_COUNT, sizeof(gpu::RayMaskParams), false, false, 0},
    {"ray_mask/mask_coverage", HMB_MASK_COVERAGE_BINDING_COUNT, sizeof(gpu::RayMaskParams), false, false,
     HMB_MASK_COVERAGE_TEXEL_BUFFERS},
    {"ray_mask/list_mask_blocks", HMB_LIST_MASK_BLOCKS_BINDING_COUNT, sizeof(gpu::RayMaskParams), false, false,
     HMB_LIST_MASK_BLOCKS_TEXEL_BUFFERS},
    {"ray_mask/list_range_blocks", HMB_RANGE_BLOCKS_BINDING_COUNT, sizeof(gpu::RayMaskParams), false},
    {"ray_mask/size_list_dispatch", HMB_SIZE_LIST_BINDING_COUNT, sizeof(gpu::SizeListParams), false},
    {"shutter_rays/list_moving_tiles", HMB_MOVING_TILES_BINDING_COUNT, sizeof(gpu::MovingTilesParams), false},
    {"reveal/reveal_background", HMB_REVEAL_BINDING_COUNT, sizeof(gpu::RevealParams), false, true,
     HMB_REVEAL_TEXEL_BUFFERS},
    {"shutter_rays/list_shutter_rays", HMB_SHUTTER_LIST_BINDING_COUNT, sizeof(gpu::ShutterRayListParams), false, false,
     HMB_SHUTTER_LIST_TEXEL_BUFFERS},
    {"shutter_rays/trace_shutter_rays", HMB_SHUTTER_TRACE_BINDING_COUNT, sizeof(gpu::ShutterRayTraceParams), false, true,
     HMB_TRACE_SCENE_TEXEL_BUFFERS + HMB_SCENE_TEXEL_BUFFERS},
};

using KernelPipelinesTest = VulkanTest;

bool isAddressBuild(std::string_view name) { return name.ends_with(vk::kByAddressSuffix); }

const KernelLayout& layoutOf(std::string_view name) {
  if (isAddressBuild(name)) name.remove_suffix(vk::kByAddressSuffix.size());
  for (const KernelLayout& l : kLayouts)
    if (name == l.name) return l;
  throw std::runtime_error("no layout declared in this test for kernel " + std::string(name));
}

TEST_F(KernelPipelinesTest, EveryKernelHasADeclaredLayoutAndBuilds) {
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    if (isAddressBuild(kernel.name)) continue;  // ComputeKernel picks it; see below
    const KernelLayout& layout = layoutOf(kernel.name);
    if (layout.needsInt64Atomics && !context().info().int64BufferAtomics) continue;
    const vk::ComputeKernel built(context(), kernel.name, layout.pushBytes);
    const bool fits = layout.storageBindings() <= context().limits().maxPerStageDescriptorStorageBuffers &&
                      layout.storageBindings() <= context().limits().maxDescriptorSetStorageBuffers;
    EXPECT_EQ(built.bindsByAddress(), !fits) << kernel.name;
    if (fits) {
      EXPECT_EQ(built.storageBufferCount(), layout.storageBindings()) << kernel.name;
      EXPECT_EQ(built.texelBindings().size(), layout.texelBindings) << kernel.name;
      EXPECT_EQ(built.bindings().size(), layout.bindings) << kernel.name;
    }
    if (layout.shades) {
      uint32_t untextured[HMB_SPEC_TEXTURE_PATH + 1] = {};
      EXPECT_NO_THROW(vk::ComputeKernel(context(), kernel.name, layout.pushBytes, untextured))
          << kernel.name << " without the texture path";
    }
  }
}

TEST_F(KernelPipelinesTest, ReflectionReadsWhatEachKernelDeclares) {
  uint32_t addressBuilds = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    const vk::KernelInterface reflected = vk::reflectKernel(kernel);
    const KernelLayout& layout = layoutOf(kernel.name);
    EXPECT_LE(reflected.pushConstantBytes, layout.pushBytes) << kernel.name;
    EXPECT_GE(reflected.localSize[0] * reflected.localSize[1] * reflected.localSize[2], 1u) << kernel.name;
    if (!isAddressBuild(kernel.name)) {
      EXPECT_EQ(reflected.storageBufferBindings.size(), layout.storageBindings()) << kernel.name;
      EXPECT_EQ(reflected.texelBufferBindings.size(), layout.texelBindings) << kernel.name;
      EXPECT_EQ(reflected.otherDescriptors, 0u) << kernel.name;
      EXPECT_FALSE(reflected.usesDeviceAddresses) << kernel.name << ": plain builds run without device addresses";
      continue;
    }
    EXPECT_TRUE(reflected.usesDeviceAddresses) << kernel.name;
    // An address build binds each group (trace scene, shading scene, image layer) as one table.
    ++addressBuilds;
    EXPECT_LE(reflected.storageBufferBindings.size(), 8u) << kernel.name;
    EXPECT_LT(reflected.storageBufferBindings.size(), layout.bindings) << kernel.name;
  }
  EXPECT_GE(addressBuilds, 4u);
  // encode_display: two buffers, one group of 8x8, its parameters (shared header).
  const vk::KernelInterface encode = vk::reflectKernel(vk::findKernel("output/encode_display"));
  EXPECT_EQ(encode.storageBufferBindings, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(encode.pushConstantBytes, sizeof(gpu::EncodeDisplayParams));
}

TEST_F(KernelPipelinesTest, HostsThatDisagreeWithTheKernelAreOneLineErrors) {
  const KernelLayout& layout = layoutOf("output/encode_display");
  expectError([&] { vk::ComputeKernel(context(), layout.name, layout.pushBytes - 4); },
              "bytes of push constants but its host passes");
  const vk::ComputeKernel kernel(context(), layout.name, layout.pushBytes);
  vk::Buffer one(context(), 64, vk::MemoryUse::Device, "test buffer");
  vk::FrameRecorder frame(context());
  frame.begin();
  const gpu::EncodeDisplayParams params{};
  // Buffers go to the binding numbers the kernel's header names, each once, all of them.
  const vk::Binding linear{HMB_ENCODE_DISPLAY_BINDING_LINEAR, &one}, rgba8{HMB_ENCODE_DISPLAY_BINDING_RGBA8, &one};
  expectError([&] { frame.dispatch("encode-display", kernel, {linear}, params, {1, 1, 1}); },
              "pass 'encode-display' (kernel 'output/encode_display') leaves binding 1 unbound");
  expectError([&] { frame.dispatch("encode-display", kernel, {linear, linear, rgba8}, params, {1, 1, 1}); },
              "binds binding 0 twice");
  expectError([&] { frame.dispatch("encode-display", kernel, {linear, rgba8, {7, &one}}, params, {1, 1, 1}); },
              "binds binding 7, which the kernel does not declare");
  expectError([&] { frame.dispatch("encode-display", kernel, {linear, {HMB_ENCODE_DISPLAY_BINDING_RGBA8, nullptr}},
                                   params, {1, 1, 1}); },
              "binds an empty buffer at binding 1");
}

// A kernel is made once per context: a second pass asking for it with the same push constants
// and specialization shares the pipeline; another specialization, or another context, makes its
// own; a failed build keeps nothing.
TEST_F(KernelPipelinesTest, EachKernelIsMadeOncePerContextAndSpecialization) {
  const KernelLayout& layout = layoutOf("bvh/build_level");
  // The GPU shape of the level kernel (shared atomics) at two workgroup sizes.
  const uint32_t eightLanes[] = {8u, 0u};
  const uint32_t sixteenLanes[] = {16u, 0u};
  const vk::ComputeKernel first(context(), layout.name, layout.pushBytes, eightLanes);
  const size_t kept = context().kernelStore().size();
  const vk::ComputeKernel again(context(), layout.name, layout.pushBytes, eightLanes);
  EXPECT_EQ(first.pipeline(), again.pipeline());
  EXPECT_EQ(first.layout(), again.layout());
  EXPECT_EQ(context().kernelStore().size(), kept);
  const vk::ComputeKernel wider(context(), layout.name, layout.pushBytes, sixteenLanes);
  EXPECT_NE(first.pipeline(), wider.pipeline());
  EXPECT_EQ(context().kernelStore().size(), kept + 1);
  expectError([&] { vk::ComputeKernel(context(), layout.name, layout.pushBytes - 4, eightLanes); },
              "bytes of push constants but its host passes");
  EXPECT_EQ(context().kernelStore().size(), kept + 1);
  vk::ContextOptions options;
  options.validation = true;
  const vk::Context other(options);
  const vk::ComputeKernel elsewhere(other, layout.name, layout.pushBytes, eightLanes);
  EXPECT_NE(elsewhere.pipeline(), first.pipeline());
  EXPECT_EQ(other.kernelStore().size(), 1u);
  EXPECT_EQ(other.validationErrors(), 0u);
}

// A device that takes fewer storage buffers per stage than the widest kernel: a kernel whose
// plain build binds more runs its address build where it has one that fits, and pipeline
// creation refuses the others in one line naming the kernel and the limit.
// Every build of every kernel declares SignedZeroInfNanPreserve for 32-bit floats
// (kernels/shared/float_controls.glsl): without it a driver may fold the kernels' isnan and
// isinf tests away, and bad input would reach the images.
TEST(KernelFloatControlsTest, EveryEmbeddedKernelKeepsNanAndInfinity) {
  ASSERT_FALSE(vk::embeddedKernels().empty());
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels())
    EXPECT_TRUE(keepsNanAndInfinity(std::span(kernel.words, kernel.wordCount)))
        << kernel.name << " does not keep NaN and infinity in 32-bit floats";
}

TEST(KernelLimitsTest, APretendDeviceWithFewerStorageBuffersTakesAddressBuildsOrRefusesInOneLine) {
  uint32_t widest = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels())
    widest = std::max(widest, uint32_t(vk::reflectKernel(kernel).storageBufferBindings.size()));
  ASSERT_GE(widest, 2u);
  const uint32_t limit = widest - 1;
  vk::ContextOptions options;
  options.validation = true;
  options.storageBufferLimit = limit;
  vk::Context small(options);
  ASSERT_EQ(small.limits().maxPerStageDescriptorStorageBuffers, limit);
  uint32_t switched = 0, refused = 0;
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    if (isAddressBuild(kernel.name)) continue;
    const KernelLayout& layout = layoutOf(kernel.name);
    if (layout.needsInt64Atomics && !small.info().int64BufferAtomics) continue;
    const vk::EmbeddedKernel* byAddress = vk::findKernelIfBuilt(std::string(kernel.name) + std::string(vk::kByAddressSuffix));
    if (layout.storageBindings() <= limit) {
      const vk::ComputeKernel built(small, kernel.name, layout.pushBytes);
      EXPECT_FALSE(built.bindsByAddress()) << kernel.name;
    } else if (byAddress && vk::reflectKernel(*byAddress).storageBufferBindings.size() <= limit &&
               small.info().bufferDeviceAddress) {
      ++switched;
      const vk::ComputeKernel built(small, kernel.name, layout.pushBytes);
      EXPECT_TRUE(built.bindsByAddress()) << kernel.name;
      EXPECT_LE(built.storageBufferCount(), limit) << kernel.name;
    } else {
      ++refused;
      expectError([&] { vk::ComputeKernel(small, kernel.name, layout.pushBytes); },
                  "kernel '" + std::string(kernel.name) + "' needs " + std::to_string(layout.storageBindings()) +
                      " storage buffers in one stage; the device allows " + std::to_string(limit) +
                      " (maxPerStageDescriptorStorageBuffers)");
    }
  }
  EXPECT_GE(switched + refused, 1u);
  EXPECT_EQ(small.validationErrors(), 0u);
}

// Mali and other GPUs allow 8 storage buffers per stage: every kernel fits there, through its
// address build where it has one, save those still listed here (docs/devices.md).
// Every kernel builds on a device with 8 storage buffers per stage (Mali's limit): plain builds
// fit, and the kernels that bind groups of buffers switch to their address builds.
TEST(KernelLimitsTest, EveryKernelBuildsOnADeviceWithEightStorageBuffers) {
  constexpr uint32_t kMali = 8;
  vk::ContextOptions options;
  options.validation = true;
  options.storageBufferLimit = kMali;
  vk::Context small(options);
  for (const vk::EmbeddedKernel& kernel : vk::embeddedKernels()) {
    if (isAddressBuild(kernel.name)) continue;
    const KernelLayout& layout = layoutOf(kernel.name);
    if (layout.needsInt64Atomics && !small.info().int64BufferAtomics) continue;
    const bool hasAddressBuild =
        vk::findKernelIfBuilt(std::string(kernel.name) + std::string(vk::kByAddressSuffix)) != nullptr;
    if (!hasAddressBuild) {
      EXPECT_LE(layout.storageBindings(), kMali) << kernel.name;
    } else if (!small.info().bufferDeviceAddress) {
      continue;
    }
    EXPECT_NO_THROW({
      const vk::ComputeKernel built(small, kernel.name, layout.pushBytes);
      EXPECT_LE(built.storageBufferCount(), kMali) << kernel.name;
    }) << kernel.name;
  }
  EXPECT_EQ(small.validationErrors(), 0u);
}

// A kernel built per combination of its switches: each combination once, each its own build,
// and more switches than constant ids fit in is a one-line error.
using KernelVariantsTest = VulkanTest;

TEST_F(KernelVariantsTest, EachCombinationOfSwitchesIsBuiltOnce) {
  const vk::KernelVariants gather(context(), "mblur/gather", sizeof(gpu::GatherParams));
  const vk::ComputeKernel& straight = gather.with({false, false, true});
  EXPECT_EQ(&gather.with({false, false, true}), &straight);
  const vk::ComputeKernel& curved = gather.with({false, true, true});
  EXPECT_NE(&curved, &straight);
  EXPECT_EQ(&gather.with({false, true, true}), &curved);
  EXPECT_NE(&gather.with({true, false, true}), &straight);
  EXPECT_EQ(curved.bindings(), straight.bindings());
  std::initializer_list<bool> tooMany = {true, true, true, true, true, true, true, true, true, true, true,
                                         true, true, true, true, true, true, true, true, true, true, true,
                                         true, true, true, true, true, true, true, true, true, true, true};
  expectError([&] { gather.with(tooMany); }, "more than 32");
}

}  // namespace
}  // namespace hmb::test
