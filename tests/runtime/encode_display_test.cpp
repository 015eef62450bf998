// The encode_display kernel against its plain C++ reference (hmb::io::encodeDisplay).
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/image.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using EncodeDisplayTest = VulkanTest;

std::vector<uint8_t> encodeOnDevice(const std::vector<glm::vec4>& linear, uint32_t width, uint32_t height) {
  vk::Context& ctx = VulkanTest::context();
  vk::Buffer in(ctx, linear.size() * sizeof(glm::vec4), vk::MemoryUse::Device, "linear");
  vk::Buffer out(ctx, linear.size() * sizeof(uint32_t), vk::MemoryUse::Device, "rgba8");
  in.upload(std::span<const glm::vec4>(linear));
  passes::EncodeDisplayPass pass(ctx);
  vk::FrameRecorder frame(ctx);
  frame.begin();
  pass.record(frame, in, out, width, height);
  frame.submitAndWait();
  const auto packed = out.download<uint32_t>();
  std::vector<uint8_t> bytes(packed.size() * 4);
  for (size_t i = 0; i < packed.size(); ++i)
    for (int c = 0; c < 4; ++c) bytes[4 * i + c] = uint8_t(packed[i] >> (8 * c));
  return bytes;
}

// Fails on any channel that differs by more than one step (pow() on the device may round
// differently from the host exactly at a quantization boundary), and when more than
// `offByOneFraction` of the channels differ at all.
void expectMatchesReference(const std::vector<glm::vec4>& linear, uint32_t width, uint32_t height,
                            double offByOneFraction = 0.001) {
  const auto device = encodeOnDevice(linear, width, height);
  const io::Rgba8Image reference = io::encodeDisplay(width, height, linear);
  ASSERT_EQ(device.size(), reference.pixels.size());
  size_t offByOne = 0;
  for (size_t i = 0; i < device.size(); ++i) {
    const int diff = std::abs(int(device[i]) - int(reference.pixels[i]));
    ASSERT_LE(diff, 1) << "channel " << i << " input " << linear[i / 4][i % 4];
    offByOne += diff;
  }
  EXPECT_LE(double(offByOne), offByOneFraction * double(device.size())) << "too many channels off by one step";
}

TEST_F(EncodeDisplayTest, RandomValuesMatchTheReference) {
  const uint32_t width = 97, height = 61;  // partial work groups on both axes
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> wide(-0.5f, 1.5f);
  std::vector<glm::vec4> linear(width * height);
  for (auto& p : linear) p = {wide(rng), wide(rng), wide(rng), wide(rng)};
  expectMatchesReference(linear, width, height);
}

TEST_F(EncodeDisplayTest, AdversarialValuesMatchTheReference) {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float denormal = std::numeric_limits<float>::denorm_min();
  const std::vector<float> specials = {0.0f, -0.0f, 1.0f, -1.0f, 2.0f, inf, -inf, nan, denormal, -denormal,
                               0.0031308f, std::nextafter(0.0031308f, 0.0f), std::nextafter(0.0031308f, 1.0f),
                               1e-30f, 1e30f, -1e30f, std::nextafter(1.0f, 0.0f), std::nextafter(1.0f, 2.0f)};
  std::vector<glm::vec4> linear;
  for (float v : specials) linear.emplace_back(v, v, v, v);
  // Values special to the transform (non-finite, out of range, the linear/power boundary)
  // must encode exactly as the reference does.
  expectMatchesReference(linear, static_cast<uint32_t>(linear.size()), 1, 0.0);

  // Values whose encoding lands exactly half-way between two 8-bit steps: there either
  // neighbour is right, so only the one-step bound holds.
  linear.clear();
  for (int step = 0; step < 255; ++step) {
    const float srgb = (step + 0.5f) / 255.0f;
    const float v = srgb <= 0.04045f ? srgb / 12.92f : std::pow((srgb + 0.055f) / 1.055f, 2.4f);
    linear.emplace_back(v, v, v, srgb);
  }
  expectMatchesReference(linear, static_cast<uint32_t>(linear.size()), 1, 1.0);
}

TEST_F(EncodeDisplayTest, SinglePixelImage) {
  expectMatchesReference({glm::vec4(0.5f, 0.25f, 0.125f, 1.0f)}, 1, 1);
}

}  // namespace
}  // namespace hmb::test
