// The whole pipeline of every method on every reference scene under the Khronos validation
// layer with synchronization validation on (the fixture's context): not one error and not one
// warning. Other tests fail on errors only; this one holds every message to zero.
#include <string>

#include <gtest/gtest.h>

#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "scenes/reference_scenes.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using ValidationTest = VulkanTest;

// Renders every method on every reference scene; each render must leave no message.
void expectEveryMethodSilent(vk::Context& context) {
  Renderer renderer(context);
  for (const std::string& name : scene::referenceSceneNames()) {
    const scene::Scene scene = scene::loadScene(name);
    for (const std::string& method : methodNames()) {
      const uint32_t errors = context.validationErrors(), warnings = context.validationWarnings();
      RenderSettings settings;
      settings.method = parseMethod(method);
      settings.width = 64;
      settings.height = 36;
      settings.reference.samplesPerPixel = 2;
      const RenderResult result = renderer.render(scene, settings);
      EXPECT_TRUE(result.frameMilliseconds.has_value() || !context.info().timestamps) << name << " " << method;
      EXPECT_EQ(context.validationErrors() - errors, 0u) << name << " " << method;
      EXPECT_EQ(context.validationWarnings() - warnings, 0u) << name << " " << method;
    }
  }
  if (::testing::Test::HasFailure())
    for (const std::string& message : context.validationMessages()) ADD_FAILURE() << message;
}

TEST_F(ValidationTest, EveryMethodOnEveryReferenceSceneRunsWithoutAValidationMessage) {
  ASSERT_TRUE(context().validationEnabled());
  expectEveryMethodSilent(context());
}

// The same with every kernel that has an address build running it (its groups of buffers bound
// as tables of device addresses), on a device pretending a discrete GPU's memory (no host
// access to its working memory, a 256 MiB BAR heap): staging copies and tables under
// synchronization validation too.
TEST(ValidationByAddressTest, EveryMethodByAddressOnADiscreteLayoutRunsWithoutAValidationMessage) {
  vk::ContextOptions options;
  options.validation = true;
  options.synchronizationValidation = true;
  options.bindByAddress = true;
  options.hostVisibleDeviceLocalBytes = 256ull << 20;
  vk::Context context(options);
  if (!context.info().bufferDeviceAddress) GTEST_SKIP() << "the device has no buffer device addresses";
  ASSERT_TRUE(context.validationEnabled());
  expectEveryMethodSilent(context);
}

}  // namespace
}  // namespace hmb::test
