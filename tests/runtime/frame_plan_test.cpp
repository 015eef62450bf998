#include <gtest/gtest.h>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::test {
namespace {

TEST(FramePlanTest, RecordsRunAndSkippedPassesInOrder) {
  FramePlan plan;
  plan.run("raster");
  plan.skip("ray-reveal", "the ray mask is empty");
  plan.run("gather");
  ASSERT_EQ(plan.passes().size(), 3u);
  EXPECT_TRUE(plan.runs("raster"));
  EXPECT_FALSE(plan.runs("ray-reveal"));
  EXPECT_EQ(plan.passes()[1].reason, "the ray mask is empty");
  EXPECT_EQ(plan.passes()[2].name, "gather");
  EXPECT_THROW(plan.run("raster"), Error);
}

TEST(FramePlanTest, TimingsAttachByNameAndAccumulate) {
  FramePlan plan;
  plan.run("a");
  plan.run("b");
  plan.skip("c", "nothing moves");
  vk::FrameTimings timings;
  timings.passes = {{"a", 1.5}, {"b", 2.0}, {"a", 0.5}};
  plan.attachTimings(timings);
  EXPECT_DOUBLE_EQ(*plan.passes()[0].milliseconds, 2.0);
  EXPECT_DOUBLE_EQ(*plan.passes()[1].milliseconds, 2.0);
  EXPECT_FALSE(plan.passes()[2].milliseconds.has_value());
}

TEST(FramePlanTest, RecordingAnUnplannedOrSkippedPassIsAnError) {
  FramePlan plan;
  plan.skip("c", "nothing moves");
  vk::FrameTimings timings;
  timings.passes = {{"c", 1.0}};
  EXPECT_THROW(plan.attachTimings(timings), Error);
}

}  // namespace
}  // namespace hmb::test
