#include <string>

#include <gtest/gtest.h>

#include "runtime/error.h"
#include "runtime/io/image.h"
#include "runtime/renderer.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using RendererTest = VulkanTest;

std::string errorOf(const RenderSettings& settings) {
  try {
    validateRenderSettings(settings);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

TEST(RenderSettingsTest, UnknownMethodNamesTheAvailableOnes) {
  RenderSettings settings;
  settings.method = "magic";
  const std::string message = errorOf(settings);
  EXPECT_NE(message.find("unknown method 'magic'"), std::string::npos) << message;
  for (const std::string& name : methodNames()) EXPECT_NE(message.find(name), std::string::npos) << message;
}

TEST(RenderSettingsTest, EmptyAndAbsurdSizesAreRejected) {
  RenderSettings settings;
  settings.width = 0;
  EXPECT_NE(errorOf(settings).find("empty"), std::string::npos);
  settings.width = kMaxImageSide + 1;
  EXPECT_NE(errorOf(settings).find("exceeds"), std::string::npos);
  settings.width = 7;
  settings.height = 3;
  EXPECT_EQ(errorOf(settings), "");
  settings.frameTime = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NE(errorOf(settings).find("finite"), std::string::npos);
}

TEST_F(RendererTest, TestPatternFrameHasBeautyDisplayAndPlan) {
  Renderer renderer(context());
  const scene::Scene empty;
  RenderSettings settings;
  settings.method = "test-pattern";
  settings.width = 7;
  settings.height = 3;
  const RenderResult result = renderer.render(empty, settings);
  ASSERT_EQ(result.image.width, 7u);
  ASSERT_EQ(result.image.height, 3u);
  const io::ImageLayer* beauty = result.image.find("");
  ASSERT_NE(beauty, nullptr);
  ASSERT_EQ(beauty->values.size(), 7u * 3u * 4u);

  // The display image is the display transform of the beauty layer.
  std::vector<glm::vec4> linear;
  for (size_t i = 0; i < beauty->values.size(); i += 4)
    linear.emplace_back(beauty->values[i], beauty->values[i + 1], beauty->values[i + 2], beauty->values[i + 3]);
  const io::Rgba8Image expected = io::encodeDisplay(7, 3, linear);
  ASSERT_EQ(result.display.pixels.size(), expected.pixels.size());
  for (size_t i = 0; i < expected.pixels.size(); ++i)
    EXPECT_LE(std::abs(int(result.display.pixels[i]) - int(expected.pixels[i])), 1) << i;

  for (const auto& pass : result.plan.passes()) {
    EXPECT_TRUE(pass.run) << pass.name;
    if (context().info().timestamps) {
      EXPECT_TRUE(pass.milliseconds.has_value()) << pass.name;
    }
  }
  EXPECT_TRUE(result.plan.runs("test-pattern"));
  EXPECT_TRUE(result.plan.runs("encode-display"));
}

TEST_F(RendererTest, ImageLargerThanTheDeviceAllowsFailsBeforeRendering) {
  Renderer renderer(context());
  RenderSettings settings;
  // 16384^2 RGBA float is 4 GiB: beyond any single storage buffer of a 32-bit range.
  settings.width = kMaxImageSide;
  settings.height = kMaxImageSide;
  if (uint64_t(kMaxImageSide) * kMaxImageSide * 16 <= context().limits().maxStorageBufferRange)
    GTEST_SKIP() << "this device takes the largest image";
  EXPECT_THROW(renderer.render(scene::Scene{}, settings), Error);
}

}  // namespace
}  // namespace hmb::test
