#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hmblur/error.h"
#include "hmblur/renderer.h"
#include "hmblur/report.h"
#include "hmblur/system_info.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using ReportTest = VulkanTest;

TEST_F(ReportTest, ReportNamesDeviceSystemSettingsAndEveryPass) {
  Renderer renderer(context());
  scene::Scene scene;
  scene.name = "empty";
  scene.settings.softZExtent = 0.03f;
  RenderSettings settings;
  settings.width = 16;
  settings.height = 9;
  RenderResult result = renderer.render(scene, settings);
  result.plan.skip("ray-reveal", "no pixel in the ray mask");

  const nlohmann::json report = renderReport(context(), querySystemInfo(), scene, result);
  EXPECT_EQ(report["device"]["name"], context().info().name);
  EXPECT_TRUE(report["system"].contains("LP_NUM_THREADS"));
  EXPECT_FALSE(report["system"]["cpu"].get<std::string>().empty());
  EXPECT_EQ(report["resolution"]["width"], 16);
  EXPECT_FLOAT_EQ(report["scene"]["settings"]["soft_z_extent"].get<float>(), 0.03f);
  ASSERT_EQ(report["passes"].size(), result.plan.passes().size());
  for (size_t i = 0; i < result.plan.passes().size(); ++i) {
    const auto& pass = report["passes"][i];
    EXPECT_EQ(pass["name"], result.plan.passes()[i].name);
    if (pass["status"] == "skipped")
      EXPECT_EQ(pass["reason"], result.plan.passes()[i].reason);
    else
      EXPECT_TRUE(pass.contains("ms"));
  }
  EXPECT_EQ(report["passes"].back()["reason"], "no pixel in the ray mask");
  // The profile the passes chose by, and the frame's shape: one submission, waited for at its end.
  EXPECT_EQ(report["device"]["profile"]["name"], context().profile().name);
  const nlohmann::json& frame = report["frame"];
  for (const char* key : {"dispatches", "indirect_dispatches", "transfers", "barriers", "submissions", "host_waits",
                          "dependent_chain"})
    EXPECT_TRUE(frame.contains(key)) << key;
  EXPECT_GT(frame["dispatches"].get<int>(), 0);
  EXPECT_EQ(frame["submissions"], 1);
  EXPECT_EQ(frame["host_waits"], 1);
  EXPECT_LE(frame["dependent_chain"].get<int>(), frame["dispatches"].get<int>());
  EXPECT_GE(frame["barriers"].get<int>(), frame["dependent_chain"].get<int>());
  EXPECT_TRUE(report["setup"].is_null());
  // The empty scene has no texture: its shading path is listed as skipped, with why.
  bool texturePathListed = false;
  for (const auto& pass : report["passes"])
    if (pass["name"] == "texture-path") {
      texturePathListed = true;
      EXPECT_EQ(pass["status"], "skipped");
      EXPECT_NE(pass["reason"].get<std::string>().find("no material has a texture"), std::string::npos);
    }
  EXPECT_TRUE(texturePathListed);

  const std::string path = testing::TempDir() + "report_test.json";
  writeJson(path, report);
  std::ifstream in(path);
  EXPECT_EQ(nlohmann::json::parse(in), report);
  EXPECT_THROW(writeJson("/nonexistent-dir/x.json", report), Error);
}

TEST(SystemInfoTest, RecordsLpNumThreadsAsSet) {
  setenv("LP_NUM_THREADS", "3", 1);
  EXPECT_EQ(querySystemInfo().lpNumThreads, "3");
  unsetenv("LP_NUM_THREADS");
  EXPECT_EQ(querySystemInfo().lpNumThreads, "unset");
}

}  // namespace
}  // namespace hmb::test
