#include "tests/hybrid/hybrid_harness.h"

#include <algorithm>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/shared/layer_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/background_gather_pass.h"
#include "runtime/passes/composite_pass.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/mask_coverage_pass.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/passes/reveal_pass.h"
#include "runtime/passes/shutter_rays_pass.h"
#include "runtime/passes/tile_max_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::test::hybrid {

namespace {

template <class T>
std::vector<T> downloadFirst(const vk::Buffer& buffer, size_t count) {
  std::vector<T> values = buffer.download<T>();
  values.resize(count);
  return values;
}

template <class T>
vk::Buffer filledBuffer(vk::Context& context, size_t count, T value, const char* name) {
  return vk::uploadedBuffer(context, std::vector<T>(std::max<size_t>(count, 1), value), name);
}

// A test's per-pixel vectors as a layer's contents (black where no colour is given).
passes::LayerContents contentsOf(const std::vector<glm::vec4>& normalDepth, const std::vector<glm::vec2>& velocity,
                                 const std::vector<uint32_t>& ids, const std::vector<glm::vec4>* color) {
  passes::LayerContents c;
  for (size_t i = 0; i < ids.size(); ++i) {
    c.color.emplace_back(color ? glm::vec3(color->at(i)) : glm::vec3(0.0f));
    c.normal.emplace_back(normalDepth[i]);
    c.depth.push_back(normalDepth[i].w);
    c.velocity.push_back(velocity[i]);
    c.objectId.push_back(ids[i]);
  }
  return c;
}

// Object ids 1 where none are given: every pixel on an object, so its normal is kept.
passes::LayerContents contentsOf(const mblur::Layer& layer, const std::vector<uint32_t>* ids = nullptr) {
  return contentsOf(layer.normalDepth, layer.velocity, ids ? *ids : std::vector<uint32_t>(layer.color.size(), 1u),
                    &layer.color);
}

// A layer's shutter paths, padded to whole 16-byte records for the texel views.
vk::Buffer pathsBuffer(vk::Context& context, std::vector<glm::uvec2> paths) {
  paths.resize((paths.size() + 1) / 2 * 2);
  return vk::uploadedBuffer(context, paths, "test shutter paths");
}

passes::LayerContents contentsOf(const MaskLayer& layer) {
  passes::LayerContents c = contentsOf(layer.normalDepth, layer.velocity, layer.objectId, nullptr);
  for (size_t i = 0; i < layer.color.size() && i < c.color.size(); ++i) c.color[i] = layer.color[i];
  return c;
}

}  // namespace

namespace {

// The ray mask's passes on `layer`; `more` records after them in the same frame.
RayMaskReadback recordRayMask(vk::Context& context, const MaskLayer& layer, const passes::RayMaskParameters& parameters,
                              const std::function<void(vk::FrameRecorder&, const passes::MotionBlurInputs&,
                                                       const passes::RayMaskStage&, const passes::RayMaskParameters&)>&
                                  more) {
  const size_t pixels = size_t(layer.width) * layer.height;
  const passes::PackedLayer packed = passes::packLayer(contentsOf(layer));
  const vk::Buffer samples = vk::uploadedBuffer(context, packed.samples, "test samples");
  const vk::Buffer surfaces = vk::uploadedBuffer(context, packed.surfaces, "test surfaces");
  const vk::Buffer velocities = vk::uploadedBuffer(context, packed.velocities, "test velocities");
  passes::RayMaskStage stage(context);
  stage.prepare(layer.width, layer.height, false, parameters.listOnlyUncovered);
  std::optional<vk::Buffer> paths;
  if (!layer.shutterPaths.empty()) paths = pathsBuffer(context, layer.shutterPaths);
  const passes::MotionBlurInputs inputs{&samples, &surfaces, &velocities, layer.width, layer.height,
                                        paths ? &*paths : nullptr};
  // The mask passes start from a tile-max at the parameters' tile size, as HybridStage records
  // it: the mask's own (which lists the edge candidates) for the whole mask, the gather's for
  // the moving tiles alone.
  const passes::TileMaxPass tileMax(context);
  passes::RayMaskParameters withTiles = parameters;
  const passes::TileGrid grid = passes::tileGridFor(layer.width, layer.height, parameters.blur.tileSize);
  withTiles.blur.width = layer.width;
  withTiles.blur.height = layer.height;
  withTiles.blur.tilesX = grid.x;
  withTiles.blur.tilesY = grid.y;
  const vk::Buffer tiles(context, uint64_t(grid.count()) * sizeof(glm::vec4), vk::MemoryUse::Device, "test tile max");
  withTiles.tileMax = &tiles;
  vk::FrameRecorder frame(context);
  frame.begin();
  if (parameters.movingTilesOnly)
    tileMax.record(frame, velocities, tiles, layer.width, layer.height, parameters.blur.tileSize,
                   parameters.blur.velocityScale);
  else
    stage.recordTileMax(frame, inputs, withTiles);
  stage.record(frame, inputs, withTiles);
  if (more) more(frame, inputs, stage, withTiles);
  frame.submitAndWait();

  RayMaskReadback out;
  out.edges = passes::unpackEdgeMask(stage.edges().download<uint32_t>(), pixels);
  out.maskValues = passes::unpackRayMask(stage.mask().download<uint32_t>(), pixels);
  out.mask.resize(pixels);
  for (size_t i = 0; i < pixels; ++i) out.mask[i] = out.maskValues[i] != HMB_MASK_NONE ? 1u : 0u;
  out.counters = stage.counters().download<gpu::RayMaskCounters>().at(0);
  out.list = downloadFirst<uint32_t>(stage.list(), std::min<size_t>(out.counters.maskCount, pixels));
  const std::vector<uint32_t> all = downloadFirst<uint32_t>(stage.list(), pixels);
  out.unrevealedList.assign(all.end() - std::min<size_t>(out.counters.unrevealedCount, pixels), all.end());
  out.candidates = downloadFirst<uint32_t>(stage.candidates(), std::min<size_t>(out.counters.candidateCount, pixels));
  out.rangeBlocks = downloadFirst<uint32_t>(stage.rangeBlocks(), std::min<size_t>(out.counters.rangeBlockCount, pixels));
  if (parameters.listOnlyUncovered && !parameters.movingTilesOnly)
    out.coverageList =
        downloadFirst<uint32_t>(stage.coverageList(), std::min<size_t>(out.counters.coverageCount, pixels));
  out.tileMax = tiles.download<glm::vec4>();
  out.movingTiles = downloadFirst<uint32_t>(stage.movingTiles(), std::min<size_t>(out.counters.tileCount, pixels));
  return out;
}

}  // namespace

RayMaskReadback runRayMask(vk::Context& context, const MaskLayer& layer, const passes::RayMaskParameters& parameters) {
  return recordRayMask(context, layer, parameters, nullptr);
}

ShutterRayListReadback runShutterRayList(vk::Context& context, const MaskLayer& layer,
                                         const passes::RayMaskParameters& parameters, uint32_t strata,
                                         std::optional<uint32_t> groupsWanted, uint32_t rayBudget) {
  passes::ShutterRaysPass pass(context);
  pass.prepare(layer.width, layer.height, rayBudget);
  const RayMaskReadback mask = recordRayMask(
      context, layer, parameters,
      [&](vk::FrameRecorder& frame, const passes::MotionBlurInputs& inputs, const passes::RayMaskStage& stage,
          const passes::RayMaskParameters& p) {
        pass.recordList(frame, inputs, p.blur, *p.tileMax, stage, strata, groupsWanted);
        if (rayBudget != 0) pass.recordBudget(frame);
      });
  ShutterRayListReadback out;
  out.maskCounters = mask.counters;
  out.counters = pass.counters().download<gpu::ShutterRayCounters>().at(0);
  const size_t pixels = size_t(layer.width) * layer.height;
  out.rays.assign(pixels, 0u);
  const size_t listed = std::min<size_t>(out.counters.count, pixels);
  const std::vector<uint32_t> entries = downloadFirst<uint32_t>(pass.list(), listed);
  const std::vector<uint32_t> priorities =
      rayBudget != 0 ? downloadFirst<uint32_t>(pass.priorities(), listed) : std::vector<uint32_t>();
  if (rayBudget != 0) out.priorities.assign(pixels, 0u);
  for (size_t slot = 0; slot < entries.size(); ++slot) {
    const uint32_t entry = entries[slot];
    const uint32_t pixel = gpu::shutterRayEntryPixel(entry);
    if (pixel >= pixels) {
      ADD_FAILURE() << "shutter ray list entry " << entry << " names no pixel";
      continue;
    }
    EXPECT_EQ(out.rays[pixel], 0u) << "pixel " << pixel << " listed twice";
    out.rays[pixel] = gpu::shutterRayEntryRays(entry);
    if (rayBudget != 0) out.priorities[pixel] = priorities[slot];
  }
  if (rayBudget == 0) return out;
  out.budget = pass.budgetState().download<gpu::ShutterRayBudget>().at(0);
  out.keptCounters = downloadFirst<gpu::ShutterRayCounters>(pass.keptCounters(), 1).at(0);
  out.kept.assign(pixels, false);
  for (const uint32_t entry : downloadFirst<uint32_t>(pass.tracedList(), std::min<size_t>(out.keptCounters.count, pixels))) {
    const uint32_t pixel = gpu::shutterRayEntryPixel(entry);
    if (pixel >= pixels || out.rays[pixel] != gpu::shutterRayEntryRays(entry) || out.kept[pixel]) {
      ADD_FAILURE() << "kept entry " << entry << " is not a listed pixel's, or is kept twice";
      continue;
    }
    out.kept[pixel] = true;
  }
  return out;
}

std::vector<glm::vec4> runGather(vk::Context& context, const mblur::Layer& layer,
                                 const std::vector<glm::vec4>& neighborMax, const GatherRun& run,
                                 const passes::PostProcessSettings& settings) {
  const size_t pixels = size_t(layer.width) * layer.height;
  auto imageLayer = [&](const mblur::Layer& l, const std::vector<uint32_t>* ids, const char* name) {
    const passes::PackedLayer packed = passes::packLayer(contentsOf(l, ids));
    return passes::ImageLayer(vk::uploadedBuffer(context, packed.samples, std::string(name) + " samples"),
                              vk::uploadedBuffer(context, packed.surfaces, std::string(name) + " surfaces"),
                              vk::uploadedBuffer(context, packed.velocities, std::string(name) + " velocities"));
  };
  const passes::ImageLayer raster = imageLayer(layer, run.objectId, "test raster");
  const vk::Buffer tiles = vk::uploadedBuffer(context, neighborMax, "test neighbor max");
  const vk::Buffer output = filledBuffer(context, pixels, run.sentinel, "test output");
  // Packed as the ray mask's buffer holds it (2 bits a pixel). For the coverage composite, as the
  // range check marks them: every mask pixel HMB_MASK_UNREVEALED, for mask_coverage to turn.
  const bool masksCoverage = run.objectId && run.composite == passes::HybridComposite::Coverage;
  std::vector<uint32_t> maskValues(std::max<size_t>(pixels, 1), HMB_MASK_NONE);
  if (run.mask)
    for (size_t i = 0; i < pixels; ++i)
      maskValues[i] = masksCoverage && (*run.mask)[i] != HMB_MASK_NONE ? HMB_MASK_UNREVEALED : (*run.mask)[i];
  const vk::Buffer mask = vk::uploadedBuffer(context, passes::packRayMask(maskValues), "test mask");
  gpu::GatherParams params = passes::gatherParams(settings, layer.width, layer.height, run.maskWeights);
  // Along curved paths the raster's paths go with it, as HybridStage binds them.
  std::optional<vk::Buffer> paths;
  if (!layer.shutterPaths.empty()) paths = pathsBuffer(context, layer.shutterPaths);
  if (paths && settings.motionPath == passes::MotionPath::Curved) params.flags |= HMB_GATHER_FLAG_CURVED_PATH;
  const vk::Buffer* pathsOrNull = paths ? &*paths : nullptr;
  vk::FrameRecorder frame(context);
  frame.begin();
  if (run.objectId) {
    const bool coverage = run.composite == passes::HybridComposite::Coverage;
    if (!run.mask || run.list) throw std::runtime_error("the composite needs the mask and no list");
    if (coverage ? !run.revealed : !run.background)
      throw std::runtime_error("the coverage composite needs a revealed layer, the weights one a background");
    const passes::MotionBlurInputs inputs{&raster.samples(), &raster.surfaces(), &raster.velocities(), layer.width,
                                          layer.height, pathsOrNull};
    // As HybridStage records it: with the coverage form, mask_coverage over the mask's pixels
    // and list_mask_blocks (which split the list between its front, the pixels to reveal, and
    // its back); the post-process gather outside the mask; then the background gather, which
    // blends the coverage composite at the list's front, and the composite (the coverage form
    // at the list's back, the weights form over the whole mask, all at the front as range_check
    // lists it).
    std::vector<uint32_t> list(std::max<size_t>(pixels, 1), 0u), maskPixels;
    for (uint32_t i = 0; i < pixels; ++i)
      if ((*run.mask)[i] != HMB_MASK_NONE) {
        list[maskPixels.size()] = i;
        maskPixels.push_back(i);
      }
    const uint32_t count = uint32_t(maskPixels.size());
    const vk::Buffer listBuffer = vk::uploadedBuffer(context, list, "test mask list");
    const vk::Buffer counters = vk::uploadedBuffer(
        context, std::vector<gpu::RayMaskCounters>{coverage ? coverageDispatchFor(count) : dispatchFor(count)},
        "test mask counters");
    if (maskPixels.empty()) maskPixels.push_back(0u);  // unread: the count is 0
    const vk::Buffer maskPixelsBuffer = vk::uploadedBuffer(context, maskPixels, "test mask pixels");
    const vk::Buffer coverageBuffer = filledBuffer(context, pixels, glm::vec4(std::numeric_limits<float>::quiet_NaN()), "test coverage");
    const vk::Buffer blockBits(context, passes::maskBlockBitsBytes(layer.width, layer.height), vk::MemoryUse::Device,
                               "test mask block bits");
    if (coverage) {
      const passes::MaskCoveragePass coveragePass(context);
      frame.fill("clear block bits", blockBits, 0u);
      coveragePass.record(frame, inputs, maskPixelsBuffer, counters, coverageBuffer, mask, blockBits, listBuffer,
                          {params, 0.0f, HMB_RANGE_CHECK_LIST_UNCOVERED, 0u, 0u});
    }
    const passes::GatherPass gather(context);
    gather.recordOutsideMask(frame, inputs, tiles, output, settings, mask);
    const passes::CompositePass composite(context);
    if (coverage) {
      const passes::ImageLayer revealed = imageLayer(*run.revealed, nullptr, "test revealed");
      const passes::BackgroundGatherPass gatherBackground(context);
      gatherBackground.record(frame, raster, revealed, tiles, mask, listBuffer, counters, output, params, pathsOrNull,
                              &coverageBuffer);
      composite.record(frame, raster, tiles, listBuffer, counters, coverageBuffer, output, params, run.composite,
                       pathsOrNull, &coverageBuffer);
      frame.submitAndWait();
    } else {
      const vk::Buffer background = vk::uploadedBuffer(context, *run.background, "test background");
      composite.record(frame, raster, tiles, listBuffer, counters, background, output, params, run.composite,
                       pathsOrNull);
      frame.submitAndWait();
    }
    if (run.coverageOut) *run.coverageOut = downloadFirst<glm::vec4>(coverageBuffer, pixels);
    if (run.maskOut) *run.maskOut = passes::unpackRayMask(mask.download<uint32_t>(), pixels);
    if (run.frontOut || run.backOut) {
      const gpu::RayMaskCounters after = counters.download<gpu::RayMaskCounters>().at(0);
      const std::vector<uint32_t> all = downloadFirst<uint32_t>(listBuffer, pixels);
      const size_t backCount = std::min<size_t>(after.unrevealedCount, pixels);
      if (run.frontOut) run.frontOut->assign(all.begin(), all.begin() + std::min<size_t>(after.maskCount, pixels));
      if (run.backOut) run.backOut->assign(all.rbegin(), all.rbegin() + backCount);
    }
  } else if (run.list) {
    const passes::ImageLayer revealed = imageLayer(run.revealed ? *run.revealed : layer, nullptr, "test revealed");
    const vk::Buffer list = vk::uploadedBuffer(context, *run.list, "test pixel list");
    const vk::Buffer counters = vk::uploadedBuffer(
        context, std::vector<gpu::RayMaskCounters>{dispatchFor(uint32_t(run.list->size()))}, "test list counters");
    const passes::BackgroundGatherPass pass(context);
    pass.record(frame, raster, revealed, tiles, mask, list, counters, output, params, pathsOrNull);
    frame.submitAndWait();
  } else {
    const passes::GatherPass pass(context);
    const passes::MotionBlurInputs inputs{&raster.samples(), &raster.surfaces(), &raster.velocities(), layer.width,
                                          layer.height, pathsOrNull};
    if (run.mask)
      pass.recordOutsideMask(frame, inputs, tiles, output, settings, mask);
    else
      pass.record(frame, inputs, tiles, output, settings);
    frame.submitAndWait();
  }
  return downloadFirst<glm::vec4>(output, pixels);
}

RevealReadback runReveal(vk::Context& context, const scene::Scene& scene, float frameTime, uint32_t width,
                         uint32_t height, const std::vector<uint32_t>& list, const passes::HybridSettings& settings,
                         const std::function<void(passes::LayerContents&)>& editRaster) {
  const size_t pixels = size_t(width) * height;
  GpuScene gpuScene(context, scene);
  gpuScene.setFrame(scene, frameTime, width, height);
  passes::GBufferStage gbuffer(context, passes::defaultVisibilityScheme(context));
  gbuffer.prepare(gpuScene, width, height);
  vk::FrameRecorder frame(context);
  passes::submitUntilRasterFits(frame, gbuffer.rasterizer(),
                                [&](vk::FrameRecorder& f) { gbuffer.record(f, gpuScene); });

  TraceScene traceScene(context, scene, frame);
  const float times[] = {frameTime};
  traceScene.setShutterTimes(scene, times, frame);
  const vk::Buffer cameraRays = vk::uploadedBuffer(
      context, std::vector<gpu::PinholeCamera>{pinholeCamera(scene, frameTime, width, height)}, "test camera rays");
  const vk::Buffer listBuffer = vk::uploadedBuffer(context, list, "test pixel list");
  const vk::Buffer counters = vk::uploadedBuffer(
      context, std::vector<gpu::RayMaskCounters>{dispatchFor(uint32_t(list.size()))}, "test counters");
  const glm::uvec4 sentinelSample = gpu::packLayerSample(glm::vec3(kSentinelColor), kSentinelDepth, kSentinelVelocity);
  const glm::uvec4 sentinelSurface =
      gpu::packLayerSurface(glm::vec3(0.0f, 0.0f, 1.0f), kSentinelId, kSentinelDepth, kSentinelVelocity);
  const passes::ImageLayer output(filledBuffer(context, pixels, sentinelSample, "test revealed samples"),
                                  filledBuffer(context, pixels, sentinelSurface, "test revealed surfaces"));

  if (editRaster) {
    passes::LayerContents contents = passes::downloadLayer(gbuffer.layer(), pixels);
    editRaster(contents);
    const passes::PackedLayer packed = passes::packLayer(contents);
    frame.begin();
    frame.write("edit the G-buffer", gbuffer.layer().samples(), std::span<const glm::uvec4>(packed.samples));
    frame.write("edit the G-buffer", gbuffer.layer().surfaces(), std::span<const glm::uvec4>(packed.surfaces));
    frame.submitAndWait();
  }

  const passes::RevealPass reveal(context);
  frame.begin();
  reveal.record(frame, traceScene, gpuScene, cameraRays, gbuffer.layer(), listBuffer, counters,
                output, width, height, settings);
  frame.submitAndWait();

  RevealReadback out;
  out.camera = gpuScene.camera();
  out.raster = readLayer(gbuffer.layer(), pixels);
  out.revealed = readLayer(output, pixels);
  out.counters = counters.download<gpu::RayMaskCounters>().at(0);
  return out;
}

MaskLayer randomMaskLayer(uint32_t width, uint32_t height, std::mt19937& rng) {
  const size_t pixels = size_t(width) * height;
  MaskLayer layer{width, height, std::vector<glm::vec4>(pixels), std::vector<glm::vec2>(pixels),
                  std::vector<uint32_t>(pixels, 1u)};
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), signed1(-1.0f, 1.0f), motion(-14.0f, 14.0f);
  auto randomNormal = [&] {
    const glm::vec3 n(signed1(rng), signed1(rng), 1.0f + unit(rng));
    return glm::normalize(n);
  };
  const glm::vec3 backgroundNormal = randomNormal();
  for (size_t i = 0; i < pixels; ++i) {
    // A far, slightly bumpy background; a quarter of its pixels drift.
    layer.normalDepth[i] =
        glm::vec4(glm::normalize(backgroundNormal + 0.05f * glm::vec3(signed1(rng), signed1(rng), 0.0f)),
                  20.0f + 2.0f * unit(rng));
    layer.velocity[i] = unit(rng) < 0.25f ? glm::vec2(signed1(rng), signed1(rng)) : glm::vec2(0.0f);
  }
  const int rectangles = 2 + int(unit(rng) * 4.0f);
  for (int r = 0; r < rectangles; ++r) {
    const auto x0 = uint32_t(unit(rng) * float(width)), y0 = uint32_t(unit(rng) * float(height));
    const uint32_t x1 = std::min(width, x0 + 1 + uint32_t(unit(rng) * float(width) / 2.0f));
    const uint32_t y1 = std::min(height, y0 + 1 + uint32_t(unit(rng) * float(height) / 2.0f));
    const glm::vec2 v = unit(rng) < 0.8f ? glm::vec2(motion(rng), motion(rng)) : glm::vec2(0.0f);
    const float depth = 1.0f + 15.0f * unit(rng);
    const float slope = 0.05f * signed1(rng);  // a tilted surface: depth varies across it
    const glm::vec3 n = randomNormal();
    const uint32_t id = 2u + uint32_t(r);
    for (uint32_t y = y0; y < y1; ++y)
      for (uint32_t x = x0; x < x1; ++x) {
        const size_t i = size_t(y) * width + x;
        layer.normalDepth[i] = glm::vec4(n, depth + slope * float(x - x0));
        layer.velocity[i] = v;
        layer.objectId[i] = id;
      }
  }
  return layer;
}

MaskLayer movingOntoStillColumns(uint32_t width, uint32_t height, uint32_t stillColumns, glm::vec2 velocity) {
  MaskLayer layer{width, height, {}, {}, {}};
  for (uint32_t y = 0; y < height; ++y)
    for (uint32_t x = 0; x < width; ++x) {
      const bool front = x + stillColumns < width;
      layer.normalDepth.emplace_back(0.0f, 0.0f, 1.0f, front ? 1.0f : 5.0f);
      layer.velocity.emplace_back(front ? velocity : glm::vec2(0.0f));
      layer.objectId.push_back(front ? 2u : 3u);
    }
  return layer;
}

MaskLayer adversarialMaskLayer(uint32_t width, uint32_t height, std::mt19937& rng) {
  constexpr float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  MaskLayer layer = randomMaskLayer(width, height, rng);
  const float velocities[] = {0.0f, 1e-31f, 1e-30f, 0.3f, -0.7f, 0.5f, 1e30f, -1e30f, 3e38f, nan, inf, -inf};
  const float depths[] = {0.0f, -1.0f, 1e-30f, 1e30f, 3e38f, 3.4e38f, nan, inf, -inf, 0.03f, 1.0f};
  const float normals[] = {nan, inf, -inf, 1e30f, -1e30f, 0.0f, 2.0f, -1.0f};
  std::uniform_int_distribution<size_t> pickV(0, std::size(velocities) - 1), pickD(0, std::size(depths) - 1),
      pickN(0, std::size(normals) - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (size_t i = 0; i < layer.velocity.size(); ++i) {
    if (unit(rng) < 0.15f) layer.velocity[i] = {velocities[pickV(rng)], velocities[pickV(rng)]};
    if (unit(rng) < 0.15f) layer.normalDepth[i].w = depths[pickD(rng)];
    if (unit(rng) < 0.05f) layer.normalDepth[i][int(unit(rng) * 3.0f) % 3] = normals[pickN(rng)];
    if (unit(rng) < 0.05f) layer.objectId[i] = 0u;
  }
  return layer;
}

}  // namespace hmb::test::hybrid
