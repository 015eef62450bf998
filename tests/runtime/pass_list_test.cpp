// passes::PassList: a stage's passes declared once. Its plan lists them in order, each run or
// skipped with its reason, a pass of several steps once; its recording records exactly what the
// plan runs, in order, a step only where its own reason is empty, a group given the frame's plan,
// a dispatch with its manifest kernel built on first use.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hmblur/frame_plan.h"
#include "kernels/manifest.h"
#include "runtime/passes/pass_list.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

struct Frame {
  bool coverage = false;  // the last size step's condition
  std::vector<std::string>* recorded = nullptr;
};

using PassListTest = VulkanTest;

std::vector<std::pair<std::string, std::string>> planOf(const FramePlan& plan) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const PlannedPass& p : plan.passes()) out.emplace_back(p.name, p.run ? "run" : p.reason);
  return out;
}

passes::PassList<Frame> exampleList(const vk::Context& context, bool clearRuns) {
  const auto note = [](std::string step) {
    return [step](vk::FrameRecorder&, const Frame& f) { f.recorded->push_back(step); };
  };
  passes::PassList<Frame> list(context);
  list.pass("clear", note("clear"), [clearRuns](const Frame&) { return clearRuns ? "" : "nothing to clear"; })
      .pass("size", note("size/first"))
      .dispatch("tile-max", kernels::kernel("mblur/tile_max"),
                [](vk::FrameRecorder&, const passes::DeclaredPass& pass, const Frame& f) {
                  f.recorded->push_back(std::string(pass.name) + ":" + pass.kernel.name());
                })
      .group(
          [](FramePlan& plan, const Frame&) {
            plan.run("gather");
            plan.skip("gather-extra", "not this frame");
          },
          [](vk::FrameRecorder&, const FramePlan& plan, const Frame& f) {
            for (const char* name : {"gather", "gather-extra"})
              if (plan.runs(name)) f.recorded->push_back(name);
          })
      .pass("size", note("size/coverage"), [](const Frame& f) { return f.coverage ? "" : "no coverage"; })
      .pass("size", note("size/last"));
  return list;
}

TEST_F(PassListTest, ThePlanListsEachPassOnceInOrderWithWhyItIsSkipped) {
  const passes::PassList<Frame> list = exampleList(context(), false);
  FramePlan plan;
  list.plan(plan, Frame{});
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"clear", "nothing to clear"}, {"size", "run"}, {"tile-max", "run"}, {"gather", "run"},
      {"gather-extra", "not this frame"}};
  EXPECT_EQ(planOf(plan), expected);
}

TEST_F(PassListTest, RecordingRecordsWhatThePlanRunsInOrder) {
  const passes::PassList<Frame> list = exampleList(context(), true);
  vk::FrameRecorder frame(context());
  for (const bool coverage : {false, true}) {
    std::vector<std::string> recorded;
    const Frame f{coverage, &recorded};
    FramePlan plan;
    list.plan(plan, f);
    list.record(frame, plan, f);
    std::vector<std::string> expected = {"clear", "size/first", "tile-max:mblur/tile_max", "gather"};
    if (coverage) expected.push_back("size/coverage");
    expected.push_back("size/last");
    EXPECT_EQ(recorded, expected) << "coverage " << coverage;
  }
}

// A plan that skips a pass (a still frame, a method's own choice) leaves it unrecorded, and a
// pass of several steps unrecorded in every step.
TEST_F(PassListTest, APassThePlanSkipsIsNotRecorded) {
  const passes::PassList<Frame> list = exampleList(context(), true);
  vk::FrameRecorder frame(context());
  FramePlan plan;
  plan.run("clear");
  plan.skip("size", "still");
  plan.skip("tile-max", "still");
  plan.skip("gather", "still");
  std::vector<std::string> recorded;
  list.record(frame, plan, Frame{true, &recorded});
  EXPECT_EQ(recorded, std::vector<std::string>{"clear"});
}

}  // namespace
}  // namespace hmb::test
