// sharp: the G-buffer's shaded colour, the shutter-close instant without blur.
#include "hmblur/frame_plan.h"
#include "hmblur/renderer.h"
#include "runtime/methods/frame_method.h"
#include "runtime/methods/raster_frame.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/shading_kernel.h"

namespace hmb {
namespace {

class SharpMethod final : public FrameMethod {
 public:
  explicit SharpMethod(FrameResources& resources) : resources_(resources) {}

  vk::FrameTimings render(const FrameRequest& request, RenderResult& result) override {
    const GpuScene scene = prepareRasterFrame(resources_, request, result);
    passes::planTexturePath(result.plan, scene);
    result.plan.run(passes::EncodeDisplayPass::kName);
    const Beauty beauty = gbufferBeauty(resources_.gbuffer);
    const vk::FrameTimings timings = recordRasterFrame(resources_, request, scene, beauty, [](vk::FrameRecorder&) {});
    collectRasterFrame(resources_, request, beauty, result);
    return timings;
  }

 private:
  FrameResources& resources_;
};

}  // namespace

std::unique_ptr<FrameMethod> makeSharpMethod(FrameResources& resources) {
  return std::make_unique<SharpMethod>(resources);
}

}  // namespace hmb
