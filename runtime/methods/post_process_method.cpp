// postprocess: the G-buffer's colour blurred along its velocities (tile-max, neighbour-max,
// then the chosen filter's gather).
#include "hmblur/buffer.h"
#include "hmblur/frame_plan.h"
#include "hmblur/renderer.h"
#include "runtime/methods/frame_method.h"
#include "runtime/methods/raster_frame.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/passes/shading_kernel.h"

namespace hmb {
namespace {

class PostProcessMethod final : public FrameMethod {
 public:
  explicit PostProcessMethod(FrameResources& resources) : resources_(resources) {}

  vk::FrameTimings render(const FrameRequest& request, RenderResult& result) override {
    const bool still = nothingMovesOnScreen(request);
    result.postprocess = postProcessSettingsFor(request.scene, request.settings);
    const GpuScene scene = prepareRasterFrame(resources_, request, result, &*result.postprocess, still);
    passes::PostProcessStage& blur = resources_.postProcess;
    blur.configure(*result.postprocess);
    FramePlan blurPlan;
    blur.plan(blurPlan);
    planBlur(result.plan, blurPlan, still);
    passes::planTexturePath(result.plan, scene);
    vk::Buffer blurred;
    if (!still) {
      blur.prepare(request.width, request.height);
      blurred = linearImageBuffer(resources_, request, "post-process colour");
    }
    result.plan.run(passes::EncodeDisplayPass::kName);
    const passes::GBufferStage& gbuffer = resources_.gbuffer;
    const Beauty beauty = still ? gbufferBeauty(gbuffer) : linearBeauty(blurred);
    const vk::FrameTimings timings = recordRasterFrame(resources_, request, scene, beauty, [&](vk::FrameRecorder& frame) {
      // A still frame's plan skips every blur pass: none is recorded.
      blur.record(frame, result.plan,
                  {&gbuffer.layer().samples(), &gbuffer.layer().surfaces(), &gbuffer.layer().velocities(),
                   request.width, request.height, gbuffer.shutterPaths()},
                  blurred);
    });
    collectRasterFrame(resources_, request, beauty, result);
    return timings;
  }

 private:
  FrameResources& resources_;
};

}  // namespace

void validatePostProcessMethod(const RenderSettings& settings) { validatePostProcessChoices(settings); }

std::unique_ptr<FrameMethod> makePostProcessMethod(FrameResources& resources) {
  return std::make_unique<PostProcessMethod>(resources);
}

}  // namespace hmb
