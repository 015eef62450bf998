// test-pattern: proves the runtime (a kernel, a buffer, the display encoding) without a scene.
#include "hmblur/buffer.h"
#include "hmblur/frame_plan.h"
#include "hmblur/renderer.h"
#include "runtime/methods/frame_method.h"
#include "runtime/methods/raster_frame.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/test_pattern_pass.h"

namespace hmb {
namespace {

class TestPatternMethod final : public FrameMethod {
 public:
  explicit TestPatternMethod(FrameResources& resources) : resources_(resources), pattern_(resources.context) {}

  vk::FrameTimings render(const FrameRequest& request, RenderResult& result) override {
    const vk::Buffer linear = linearImageBuffer(resources_, request, "beauty (linear RGBA)");
    result.plan.run(passes::TestPatternPass::kName);
    result.plan.run(passes::EncodeDisplayPass::kName);
    vk::FrameRecorder& frame = resources_.recorder;
    frame.begin();
    pattern_.record(frame, linear, request.width, request.height, request.frameTime);
    resources_.encodeDisplay.record(frame, linear, request.display, request.width, request.height);
    const vk::FrameTimings timings = frame.submitAndWait();
    result.image = beautyImage(request, linear);
    return timings;
  }

 private:
  FrameResources& resources_;
  passes::TestPatternPass pattern_;
};

}  // namespace

std::unique_ptr<FrameMethod> makeTestPatternMethod(FrameResources& resources) {
  return std::make_unique<TestPatternMethod>(resources);
}

}  // namespace hmb
