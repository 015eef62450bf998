// hybrid: the paper's method (passes::HybridStage): the post-process blur of the raster layer,
// with the background hidden behind moving objects ray traced inside the ray mask, blurred,
// and composited in. hybrid-rays, this project's extension, runs on the same stage: the same
// blur, with rays at stratified shutter times where a path crosses an edge in place of the
// mask's reveal (the settings hybridSettingsFor derives for each method say which).
#include <algorithm>

#include "hmblur/buffer.h"
#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "hmblur/renderer.h"
#include "runtime/methods/frame_method.h"
#include "runtime/methods/raster_frame.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/hybrid_stage.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/passes/shading_kernel.h"

namespace hmb {
namespace {

class HybridMethod final : public FrameMethod {
 public:
  explicit HybridMethod(FrameResources& resources)
      : resources_(resources), hybrid_(resources.context, resources.postProcess, &resources.hitShading) {}

  vk::FrameTimings render(const FrameRequest& request, RenderResult& result) override {
    const RenderSettings& settings = request.settings;
    const bool still = nothingMovesOnScreen(request);
    result.hybrid.emplace();
    result.hybrid->settings = hybridSettingsFor(request.scene, settings);
    GpuScene scene = prepareRasterFrame(resources_, request, result, &result.hybrid->settings.blur, still);
    result.postprocess = result.hybrid->settings.blur;
    passes::PostProcessStage& blur = resources_.postProcess;
    blur.configure(*result.postprocess);
    if (!(settings.skipUnneededPasses && settings.reuseAcrossFrames)) hybrid_.forgetTraceScene();
    FramePlan blurPlan;
    hybrid_.plan(blurPlan, request.scene, request.frameTime, result.hybrid->settings);
    planBlur(result.plan, blurPlan, still);
    passes::planTexturePath(result.plan, scene);

    vk::Buffer blurred;
    vk::FrameTimings timings;
    if (!still) {
      blur.prepare(request.width, request.height);
      blurred = linearImageBuffer(resources_, request, "post-process colour");
      // The trace scene's mesh trees (setup, reported apart) and its instance tree at the frame
      // time (part of the frame) are built where the plan runs them, kept where it skips them.
      const auto prepared = hybrid_.prepare(resources_.recorder, request.scene, request.frameTime, request.width,
                                            request.height, result.hybrid->settings, result.plan);
      result.hybrid->setupMilliseconds = prepared.setup.frameMilliseconds;
      if (prepared.setupShape != vk::FrameShape{}) result.setupShape = prepared.setupShape;
      // The setup passes are listed with their times, but not added to the frame's.
      timings.passes = prepared.setup.passes;
    }
    result.plan.run(passes::EncodeDisplayPass::kName);
    const passes::GBufferStage& gbuffer = resources_.gbuffer;
    const Beauty beauty = still ? gbufferBeauty(gbuffer) : linearBeauty(blurred);
    vk::appendTimings(timings, recordRasterFrame(resources_, request, scene, beauty, [&](vk::FrameRecorder& frame) {
                        if (!still)
                          hybrid_.record(frame, result.plan, gbuffer.layer(), scene, blurred, gbuffer.shutterPaths());
                      }));
    if (const auto trees = still ? std::nullopt : hybrid_.meshTreeBytes()) {
      result.memory.bvhAllocatedBytesPerTriangle = trees->allocatedPerTriangle;
      result.memory.bvhBuiltBytesPerTriangle = trees->usedPerTriangle;
    }
    collectRasterFrame(resources_, request, beauty, result);
    collectHybridLayers(request, still, result);
    return timings;
  }

 private:
  // The ray mask, and what the reveal found behind the pixels it traced (black elsewhere), its
  // depth and object; all empty when the frame is still and the passes were skipped. The mask
  // is made on the device, so the passes over it are recorded every frame and sized from it:
  // when it is empty they dispatch no groups, and the plan says so.
  void collectHybridLayers(const FrameRequest& request, bool still, RenderResult& result) const {
    const uint64_t pixels = uint64_t(request.width) * request.height;
    std::vector<uint32_t> mask(pixels, 0u), revealedId(pixels, 0u), shutterRays(pixels, 0u);
    std::vector<glm::vec4> revealed(pixels, glm::vec4(0.0f)), revealedDepth(pixels, glm::vec4(0.0f));
    if (!still) {
      const passes::RayMaskCounts counts = hybrid_.rayMask().counts();
      result.hybrid->edgeCandidates = counts.edgeCandidates;
      result.hybrid->rangeBlocks = counts.rangeBlocks;
      result.hybrid->maskPixels = counts.maskPixels;
      result.hybrid->revealedPixels = counts.listedPixels;
      result.hybrid->revealRays = counts.revealRays;
      result.cutTraces = hybrid_.cutTraces();
      // With the shutter rays the mask's own passes and the reveal are skipped (the plan says
      // why), and their buffers not made: the layers stay empty.
      const bool masks = result.plan.runs(passes::RayMaskStage::kRangeCheck);
      if (masks) {
        mask = passes::unpackRayMask(hybrid_.rayMask().mask().download<uint32_t>(), pixels);
        const passes::ImageLayer& layer = hybrid_.revealed();
        const passes::LayerContents revealedAll = passes::downloadLayer(layer, pixels);
        std::vector<uint32_t> traced = hybrid_.rayMask().list().download<uint32_t>();
        traced.resize(std::min<size_t>(traced.size(), counts.listedPixels));
        for (const uint32_t i : traced) {
          if (i >= pixels) continue;
          revealed[i] = glm::vec4(revealedAll.color[i], 1.0f);
          revealedDepth[i] = glm::vec4(revealedAll.depth[i], 0.0f, 0.0f, 0.0f);
          revealedId[i] = revealedAll.objectId[i];
        }
      }
      if (hybrid_.tracesShutterRays()) {
        const passes::ShutterRayCounts shutter = hybrid_.shutterRays().counts();
        result.hybrid->shutterRayPixels = shutter.pixels;
        result.hybrid->shutterRayPixelsTraced = shutter.tracedPixels;
        result.hybrid->shutterRays = shutter.rays;
        std::vector<uint32_t> entries = hybrid_.shutterRays().tracedList().download<uint32_t>();
        entries.resize(std::min<size_t>(entries.size(), shutter.tracedPixels));
        for (const uint32_t entry : entries)
          if (const uint32_t i = gpu::shutterRayEntryPixel(entry); i < pixels) shutterRays[i] = gpu::shutterRayEntryRays(entry);
        if (shutter.pixels == 0)
          result.plan.noteNoWork(passes::HybridStage::kShutterRaysTrace, "no pixel's path crosses an edge (another object, a colour step)");
        else if (shutter.tracedPixels == 0)
          result.plan.noteNoWork(passes::HybridStage::kShutterRaysTrace, "the ray budget holds no listed pixel's rays");
      }
      if (masks && result.hybrid->edgeCandidates == 0)
        result.plan.noteNoWork(passes::RayMaskStage::kEdges, "no pixel ends on a deeper object (eqs. 1-2): no Sobel");
      if (masks && result.hybrid->revealedPixels == 0) {
        const std::string reason = result.hybrid->maskPixels == 0
                                       ? "the ray mask is empty: no ray traced"
                                       : "no mask pixel's composite meets the background: no ray traced";
        result.plan.noteNoWork(passes::RevealPass::kName, reason);
        result.plan.noteNoWork(passes::HybridStage::kGatherBackground, reason);
      }
      // The coverage composite's pass takes the mask pixels not revealed (the background gather
      // blends the others); the weights form's, every mask pixel.
      const bool coverage = result.hybrid->settings.composite == passes::HybridComposite::Coverage;
      if (masks && coverage && result.hybrid->maskPixels != 0 &&
          result.hybrid->maskPixels == result.hybrid->revealedPixels)
        result.plan.noteNoWork(passes::HybridStage::kComposite,
                               "every mask pixel's composite meets the background: the background gather blended them");
      if (masks && result.hybrid->maskPixels == 0) {
        result.plan.noteNoWork(passes::HybridStage::kComposite,
                               "the ray mask is empty: the post-process gather's image stands");
        if (result.plan.runs(passes::RayMaskStage::kCoverage)) {
          result.plan.noteNoWork(passes::RayMaskStage::kCoverage, "the ray mask is empty: no coverage to find");
          result.plan.noteNoWork(passes::RayMaskStage::kListBlocks, "the ray mask is empty: no pixel to list");
        }
      }
    }
    result.image.layers.push_back(io::ImageLayer{"rayMask", {"mask"}, true, {}, std::move(mask)});
    result.image.layers.push_back(vec4Layer("revealed", {"R", "G", "B"}, revealed));
    result.image.layers.push_back(vec4Layer("revealedDepth", {"Z"}, revealedDepth));
    result.image.layers.push_back(io::ImageLayer{"revealedObjectId", {"id"}, true, {}, std::move(revealedId)});
    // Rays each pixel took over the shutter (0: the composite's colour stands).
    result.image.layers.push_back(io::ImageLayer{"shutterRays", {"rays"}, true, {}, std::move(shutterRays)});
  }

  FrameResources& resources_;
  passes::HybridStage hybrid_;
};

}  // namespace

void validateHybridMethod(const RenderSettings& settings) { validateHybridChoices(settings); }

std::unique_ptr<FrameMethod> makeHybridMethod(FrameResources& resources) {
  return std::make_unique<HybridMethod>(resources);
}

}  // namespace hmb
