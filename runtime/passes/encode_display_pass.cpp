#include "runtime/passes/encode_display_pass.h"

#include "kernels/manifest.h"
#include "kernels/output/encode_display.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

namespace {
constexpr uint32_t kFromSamples[] = {1u};  // HMB_SPEC_ENCODE_LAYER_SAMPLES
}

EncodeDisplayPass::EncodeDisplayPass(const vk::Context& context)
    : linearKernel_(context, kernels::kernel("output/encode_display")),
      samplesKernel_(context, kernels::kernel("output/encode_display"), kFromSamples) {}

void EncodeDisplayPass::record(vk::FrameRecorder& frame, const vk::Buffer& input, const vk::Buffer& rgba8,
                               uint32_t width, uint32_t height, DisplaySource source) const {
  const gpu::EncodeDisplayParams params{width, height, 0, 0};
  const vk::ComputeKernel& kernel = source == DisplaySource::LayerSamples ? samplesKernel_ : linearKernel_;
  frame.dispatch(kName, kernel, {{HMB_ENCODE_DISPLAY_BINDING_LINEAR, &input}, {HMB_ENCODE_DISPLAY_BINDING_RGBA8, &rgba8}},
                 params,
                 {vk::groupsFor(width, HMB_ENCODE_DISPLAY_GROUP_X), vk::groupsFor(height, HMB_ENCODE_DISPLAY_GROUP_Y),
                  1});
}

}  // namespace hmb::passes
