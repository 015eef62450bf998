// The whole pipeline of every method on every reference scene under the Khronos validation
// layer with synchronization validation on (the fixture's context): not one error and not one
// warning. Other tests fail on errors only; this one holds every message to zero.
#include <string>

#include <gtest/gtest.h>

#include "runtime/renderer.h"
#include "scenes/load_scene.h"
#include "scenes/reference_scenes.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using ValidationTest = VulkanTest;

TEST_F(ValidationTest, EveryMethodOnEveryReferenceSceneRunsWithoutAValidationMessage) {
  ASSERT_TRUE(context().validationEnabled());
  Renderer renderer(context());
  for (const std::string& name : scene::referenceSceneNames()) {
    const scene::Scene scene = scene::loadScene(name);
    for (const std::string& method : methodNames()) {
      const uint32_t errors = context().validationErrors(), warnings = context().validationWarnings();
      RenderSettings settings;
      settings.method = parseMethod(method);
      settings.width = 64;
      settings.height = 36;
      settings.reference.samplesPerPixel = 2;
      const RenderResult result = renderer.render(scene, settings);
      EXPECT_TRUE(result.frameMilliseconds.has_value() || !context().info().timestamps) << name << " " << method;
      EXPECT_EQ(context().validationErrors() - errors, 0u) << name << " " << method;
      EXPECT_EQ(context().validationWarnings() - warnings, 0u) << name << " " << method;
    }
  }
  if (HasFailure())
    for (const std::string& message : context().validationMessages()) ADD_FAILURE() << message;
}

}  // namespace
}  // namespace hmb::test
