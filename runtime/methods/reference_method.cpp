// reference: distributed ray tracing over the shutter (passes::ReferenceStage), the judge of
// every other method.
#include "hmblur/buffer.h"
#include "hmblur/frame_plan.h"
#include "hmblur/renderer.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/methods/frame_method.h"
#include "runtime/methods/raster_frame.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/reference_stage.h"
#include "runtime/passes/shading_kernel.h"

namespace hmb {
namespace {

class ReferenceMethod final : public FrameMethod {
 public:
  explicit ReferenceMethod(FrameResources& resources) : resources_(resources), reference_(resources.context, &resources.hitShading) {}

  vk::FrameTimings render(const FrameRequest& request, RenderResult& result) override {
    const RenderSettings& settings = request.settings;
    GpuScene scene(resources_.context, request.scene);
    scene.setFrame(request.scene, request.frameTime, request.width, request.height);
    if (!settings.skipUnneededPasses) {
      scene.keepTexturePath();
      scene.keepTopLevelWalk();
    }
    const vk::Buffer linear = linearImageBuffer(resources_, request, "beauty (linear RGBA)");
    if (!(settings.skipUnneededPasses && settings.reuseAcrossFrames)) reference_.forgetTraceScene();
    reference_.plan(result.plan, request.scene, request.frameTime, request.width, request.height, settings.reference);
    passes::planTexturePath(result.plan, scene);
    result.plan.run(passes::EncodeDisplayPass::kName);
    vk::FrameTimings timings =
        reference_.render(resources_.recorder, request.scene, scene, request.frameTime, request.width, request.height,
                          settings.reference, result.plan, linear, settings.onProgress);
    vk::FrameRecorder& frame = resources_.recorder;
    frame.begin();
    resources_.encodeDisplay.record(frame, linear, request.display, request.width, request.height);
    vk::appendTimings(timings, frame.submitAndWait());
    result.reference = reference_.lastProgress();
    result.cutTraces = reference_.cutTraces();
    result.image = beautyImage(request, linear);
    return timings;
  }

 private:
  FrameResources& resources_;
  passes::ReferenceStage reference_;
};

}  // namespace

void validateReferenceMethod(const RenderSettings& settings) { passes::validateReferenceSettings(settings.reference); }

std::unique_ptr<FrameMethod> makeReferenceMethod(FrameResources& resources) {
  return std::make_unique<ReferenceMethod>(resources);
}

}  // namespace hmb
