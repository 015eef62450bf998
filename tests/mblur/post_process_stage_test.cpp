// PostProcessStage: settings validation, the frame plan, size checks, and the whole stage
// against the reference pipeline for both filters.
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "hmblur/scene.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/mblur/mblur_harness.h"
#include "tests/mblur/mblur_reference.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace mblur;
using passes::PostProcessSettings;

// Every absurd value throws hmb::Error with a one-line message; the defaults pass.
TEST(MblurSettingsTest, AbsurdValuesThrowOneLineErrors) {
  EXPECT_NO_THROW(passes::validate(PostProcessSettings{}));
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::vector<std::function<void(PostProcessSettings&)>> absurd = {
      [](auto& s) { s.samples = 0; },
      [](auto& s) { s.samples = 256; },
      [](auto& s) { s.tileSize = 0; },
      [](auto& s) { s.tileSize = 1025; },
      [](auto& s) { s.filter = passes::PostProcessFilter::Jimenez, s.tileSize = 0; },
      [](auto& s) { s.neighborhood = 0; },
      [](auto& s) { s.neighborhood = 4; },
      [](auto& s) { s.neighborhood = 33; },
      [=](auto& s) { s.exposure = nan; },
      [=](auto& s) { s.exposure = inf; },
      [](auto& s) { s.exposure = -0.01f; },
      [](auto& s) { s.fps = 0.0f; },
      [](auto& s) { s.fps = -60.0f; },
      [=](auto& s) { s.fps = inf; },
      [](auto& s) { s.exposure = 1e30f, s.fps = 1e30f; },
      [](auto& s) { s.softZExtent = 0.0f; },
      [](auto& s) { s.softZExtent = -0.03f; },
      [=](auto& s) { s.softZExtent = nan; },
      [=](auto& s) { s.softZExtent = inf; },
      [](auto& s) { s.foregroundBoost = 0.0f; },
      [=](auto& s) { s.foregroundBoost = nan; },
      [=](auto& s) { s.foregroundBoost = inf; },
      [](auto& s) { s.jimenezTileJitter = 2.0f; },
      [](auto& s) { s.motionPath = passes::MotionPath::Curved, s.range = passes::GatherRange::Centered; },
      [](auto& s) { s.motionPath = passes::MotionPath::Curved, s.filter = passes::PostProcessFilter::Jimenez; },
  };
  for (size_t i = 0; i < absurd.size(); ++i) {
    PostProcessSettings s;
    absurd[i](s);
    try {
      passes::validate(s);
      ADD_FAILURE() << "case " << i << " was accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_FALSE(message.empty());
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  // Edge values that are not absurd.
  PostProcessSettings edge;
  edge.samples = 255;
  edge.tileSize = 1024;
  edge.neighborhood = 1;
  edge.exposure = 0.0f;
  EXPECT_NO_THROW(passes::validate(edge));
}

TEST(MblurSettingsTest, DefaultsFollowTheRangeAndTheScene) {
  PostProcessSettings s;
  EXPECT_EQ(s.effectiveForegroundBoost(), 30.0f);
  EXPECT_EQ(s.velocityScale(), s.exposure * s.fps);
  s.range = passes::GatherRange::Centered;
  EXPECT_EQ(s.effectiveForegroundBoost(), 1.0f);
  EXPECT_EQ(s.velocityScale(), 0.5f * s.exposure * s.fps);
  s.foregroundBoost = 4.0f;
  EXPECT_EQ(s.effectiveForegroundBoost(), 4.0f);
  s.filter = passes::PostProcessFilter::Jimenez;
  s.range = passes::GatherRange::Adapted;
  EXPECT_EQ(s.effectiveRange(), passes::GatherRange::Centered);
  EXPECT_EQ(s.effectiveTileSize(), passes::describe(passes::PostProcessFilter::Jimenez).tileSize);
  s.tileSize = 7;
  EXPECT_EQ(s.effectiveTileSize(), 7u);

  scene::Settings scene;
  scene.softZExtent = 0.005f;
  scene.fps = 240.0f;
  scene.exposure = 1.0f / 120.0f;
  const PostProcessSettings fromScene = PostProcessSettings::fromScene(scene);
  EXPECT_EQ(fromScene.softZExtent, 0.005f);
  EXPECT_EQ(fromScene.fps, 240.0f);
  EXPECT_EQ(fromScene.exposure, 1.0f / 120.0f);
}

using MblurStageTest = VulkanTest;

TEST_F(MblurStageTest, PlansItsPassesAndChecksSizes) {
  PostProcessSettings s;
  passes::PostProcessStage mcguire(context(), s);
  FramePlan plan;
  mcguire.plan(plan);
  ASSERT_EQ(plan.passes().size(), 6u);
  EXPECT_EQ(plan.passes()[0].name, "tile-max");
  EXPECT_EQ(plan.passes()[1].name, "neighbor-max");
  EXPECT_EQ(plan.passes()[2].name, "clear-gather-blocks");
  EXPECT_EQ(plan.passes()[3].name, "list-gather-blocks");
  EXPECT_EQ(plan.passes()[4].name, "gather");
  EXPECT_EQ(plan.passes()[5].name, "copy-still-blocks");

  s.filter = passes::PostProcessFilter::Jimenez;
  passes::PostProcessStage jimenez(context(), s);
  FramePlan jimenezPlan;
  jimenez.plan(jimenezPlan);
  EXPECT_EQ(jimenezPlan.passes()[2].name, "gather-jimenez");

  mcguire.prepare(81, 41);
  EXPECT_EQ(mcguire.tileGrid().x, 3u);
  EXPECT_EQ(mcguire.tileGrid().y, 2u);
  const Layer layer = stillLayer(80, 41);
  vk::Buffer samples = vk::uploadedBuffer(context(), packedSamples(layer), "s");
  vk::Buffer surfaces = vk::uploadedBuffer(context(), packedSurfaces(layer), "f");
  vk::Buffer velocities = vk::uploadedBuffer(context(), packedVelocities(layer), "v");
  vk::Buffer out(context(), layer.color.size() * sizeof(glm::vec4), vk::MemoryUse::Device, "o");
  vk::FrameRecorder frame(context());
  frame.begin();
  EXPECT_THROW(mcguire.record(frame, {&samples, &surfaces, &velocities, 80, 41}, out), Error);

  PostProcessSettings bad;
  bad.samples = 0;
  EXPECT_THROW(passes::PostProcessStage(context(), bad), Error);
}

TEST_F(MblurStageTest, WholeStageMatchesTheReferencePipeline) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), motion(-8.0f, 8.0f);
  const uint32_t width = 131, height = 77;
  Layer layer = stillLayer(width, height);
  for (size_t i = 0; i < layer.color.size(); ++i) {
    layer.color[i] = {unit(rng), unit(rng), unit(rng), 1.0f};
    layer.normalDepth[i].w = 1.0f + 9.0f * unit(rng);
    layer.velocity[i] = (i / width) % 20 < 8 ? glm::vec2(motion(rng), motion(rng)) : glm::vec2(0.0f);
  }
  for (auto filter : {passes::PostProcessFilter::McGuire, passes::PostProcessFilter::Jimenez})
    for (auto range : {passes::GatherRange::Centered, passes::GatherRange::Adapted}) {
      PostProcessSettings s;
      s.filter = filter;
      s.range = range;
      s.tileSize = 16;
      s.seed = 5;
      SCOPED_TRACE(testing::Message() << passes::filterName(filter) << " " << passes::rangeName(range));
      const auto device = runStage(context(), layer, s);
      const auto reference = postProcess(layer, nullptr, s);
      ASSERT_TRUE(allFinite(device));
      size_t off = 0;
      for (size_t i = 0; i < device.size(); ++i) off += maxAbsDifference(device[i], reference[i]) > 2e-4f;
      EXPECT_LE(off, device.size() / 200) << off << " pixels differ from the reference";
    }
}

}  // namespace
}  // namespace hmb::test
