#include "runtime/passes/test_pattern_pass.h"

#include "kernels/debug/test_pattern.h"
#include "kernels/manifest.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::passes {

TestPatternPass::TestPatternPass(const vk::Context& context)
    : kernel_(context, kernels::kernel("debug/test_pattern")) {}

void TestPatternPass::record(vk::FrameRecorder& frame, const vk::Buffer& linear, uint32_t width, uint32_t height,
                             float time) const {
  const gpu::TestPatternParams params{width, height, time, 0};
  frame.dispatch(kName, kernel_, {{HMB_TEST_PATTERN_BINDING_LINEAR, &linear}}, params,
                 {vk::groupsFor(width, HMB_TEST_PATTERN_GROUP_X), vk::groupsFor(height, HMB_TEST_PATTERN_GROUP_Y), 1});
}

}  // namespace hmb::passes
