#include "runtime/passes/encode_display_pass.h"

#include "kernels/output/encode_display.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

EncodeDisplayPass::EncodeDisplayPass(const vk::Context& context)
    : kernel_(context, "output/encode_display", sizeof(gpu::EncodeDisplayParams)) {}

void EncodeDisplayPass::record(vk::FrameRecorder& frame, const vk::Buffer& linear, const vk::Buffer& rgba8,
                               uint32_t width, uint32_t height) const {
  const gpu::EncodeDisplayParams params{width, height, 0, 0};
  frame.dispatch(kName, kernel_, {{HMB_ENCODE_DISPLAY_BINDING_LINEAR, &linear}, {HMB_ENCODE_DISPLAY_BINDING_RGBA8, &rgba8}},
                 params,
                 {vk::groupsFor(width, HMB_ENCODE_DISPLAY_GROUP_X), vk::groupsFor(height, HMB_ENCODE_DISPLAY_GROUP_Y),
                  1});
}

}  // namespace hmb::passes
