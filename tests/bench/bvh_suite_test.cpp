// hmblur-bench's bvh suite as a user runs it, on the smallest reference scene: the driver's own
// ray queries stand beside ours where the device has them, agree with Embree, and say why they
// are left out where it has not. Times are only checked to be measured, never against a bar.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hmblur/context.h"
#include "tests/bench/bench_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

bool deviceHasRayQueries() {
  const vk::Context context;
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(context.physicalDevice(), nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(context.physicalDevice(), nullptr, &count, extensions.data());
  bool query = false, structures = false;
  for (const VkExtensionProperties& e : extensions) {
    query = query || std::strcmp(e.extensionName, VK_KHR_RAY_QUERY_EXTENSION_NAME) == 0;
    structures = structures || std::strcmp(e.extensionName, VK_KHR_ACCELERATION_STRUCTURE_EXTENSION_NAME) == 0;
  }
  return query && structures;
}

TEST(BvhSuite, TheDriversRayQueriesStandBesideOursWhereItHasThem) {
  const fs::path dir = tempDir("bench_bvh");
  const std::string out = (dir / "bvh.json").string();
  const CliRun run = bench("bvh --scenes living-room --warmup 0 --repeats 1 --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(out);
  ASSERT_EQ(report.at("cases").size(), 1u);
  const nlohmann::json& c = report.at("cases").at(0);
  const std::string rayQuery = report.at("settings").at("ray_query");
  if (!deviceHasRayQueries()) {
    EXPECT_EQ(rayQuery.rfind("left out: the driver has no VK_KHR_", 0), 0u) << rayQuery;
    EXPECT_TRUE(c.at("build").at("ray_query_build_ms").is_null()) << c.dump();
    EXPECT_FALSE(c.at("coherent").contains("ray_query_mrays_per_s")) << c.dump();
    GTEST_SKIP() << "the device has no ray queries: only their absence is checked";
  }
  EXPECT_EQ(rayQuery.rfind("measured", 0), 0u) << rayQuery;
  EXPECT_GT(c.at("build").at("ray_query_build_ms").at("median").get<double>(), 0.0) << c.dump();
  for (const char* rays : {"coherent", "incoherent"}) {
    const nlohmann::json& t = c.at(rays);
    EXPECT_GT(t.at("ray_query_mrays_per_s").get<double>(), 0.0) << rays;
    EXPECT_GE(t.at("ray_query_hit_agreement").get<double>(), 0.999) << rays;
    EXPECT_EQ(t.at("ray_query_disagreements").at("ray_query_wrong"), 0) << rays;
  }
}

TEST(BvhSuite, NoRayQueryLeavesThemOutAndSaysSo) {
  const fs::path dir = tempDir("bench_bvh_no_ray_query");
  const std::string out = (dir / "bvh.json").string();
  const CliRun run = bench("bvh --scenes living-room --warmup 0 --repeats 1 --no-ray-query --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(out);
  EXPECT_EQ(report.at("settings").at("ray_query"), "left out: not asked for");
  EXPECT_FALSE(report.at("cases").at(0).at("incoherent").contains("ray_query_mrays_per_s"));
}

// The top-level tree over a scene's instances is measured beside the flattened mesh's tree, by
// stage: the living room's 10 instances go straight to one small task (no level); bistro's 321
// do so on a CPU device (HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU) and take levels first on a GPU; the
// stages lie within the whole. Bistro's moving instances inserted into its still ones' kept tree
// are timed beside. The treelet builder's build of each scene's triangles stands beside.
TEST(BvhSuite, TheTopLevelTreeOverTheScenesInstancesIsTimedByStage) {
  const fs::path dir = tempDir("bench_bvh_top_level");
  const std::string out = (dir / "bvh.json").string();
  const CliRun run = bench("bvh --scenes living-room,bistro --warmup 0 --repeats 1 --no-ray-query --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("The top-level tree over each scene's instances"), std::string::npos) << run.output;
  const nlohmann::json report = readJson(out);
  const bool cpu = report.at("device").at("profile").at("name") == "cpu";
  ASSERT_EQ(report.at("cases").size(), 2u);
  for (const nlohmann::json& c : report.at("cases")) {
    const nlohmann::json& top = c.at("top_level");
    ASSERT_TRUE(top.is_object()) << c.dump();
    const bool oneTask = c.at("scene") == "living-room" || cpu;
    EXPECT_EQ(top.at("instances"), c.at("scene") == "living-room" ? 10 : 321);
    EXPECT_EQ(top.at("device_level_ms").empty(), oneTask) << top.dump();
    EXPECT_GE(top.at("device_small_tasks").get<int>(), 1);
    if (oneTask) {
      EXPECT_EQ(top.at("device_small_tasks"), 1);
    }
    const double whole = top.at("device_ms").at("median").get<double>();
    double stages = top.at("device_small_task_ms").get<double>();
    for (const nlohmann::json& level : top.at("device_level_ms")) stages += level.get<double>();
    EXPECT_GT(stages, 0.0);
    EXPECT_LE(stages, whole * 1.0001) << top.dump();
    // Bistro's 6 moving instances are inserted into its 315 still ones' kept tree; the living
    // room's 10 instances are one tree.
    const bool split = c.at("scene") == "bistro";
    EXPECT_EQ(top.at("inserted"), split ? 6 : 0) << top.dump();
    EXPECT_EQ(top.at("insertion_ms").is_object(), split) << top.dump();
    if (split) {
      EXPECT_GT(top.at("insertion_ms").at("median").get<double>(), 0.0);
    }
    // Each build's shape: its dispatches and at least the wait at its end, for the top level and
    // the scene's whole tree.
    // The linear builder beside it: four dispatches and a sound tree, whatever the count.
    EXPECT_EQ(top.at("linear_frame").at("dispatches"), 4) << top.dump();
    EXPECT_GT(top.at("linear_ms").at("median").get<double>(), 0.0);
    EXPECT_GT(top.at("linear_sah_over_binned").get<double>(), 0.5) << top.dump();
    for (const nlohmann::json* shape : {&top.at("device_frame"), &c.at("build").at("device_frame")}) {
      EXPECT_GE(shape->at("dispatches").get<int>(), 2) << shape->dump();
      EXPECT_GE(shape->at("host_waits").get<int>(), 1) << shape->dump();
      EXPECT_GE(shape->at("submissions").get<int>(), 1) << shape->dump();
    }
    // The treelet builder beside the profile's: nine dispatches in one submission whatever the
    // scene, a sound tree, and its rays agreeing with Embree's.
    const nlohmann::json& treelets = c.at("treelet_build");
    EXPECT_EQ(treelets.at("device_frame").at("dispatches"), 9) << treelets.dump();
    EXPECT_EQ(treelets.at("device_frame").at("submissions"), 1) << treelets.dump();
    EXPECT_GT(treelets.at("device_ms").at("median").get<double>(), 0.0);
    EXPECT_GT(treelets.at("sah_over_full_sweep").get<double>(), 0.5) << treelets.dump();
    EXPECT_EQ(treelets.at("stage_ms").size(), 6u) << treelets.dump();
    for (const char* rays : {"coherent", "incoherent"})
      EXPECT_GE(treelets.at(rays).at("hit_agreement").get<double>(), 0.999) << rays << ": " << treelets.dump();
  }
}

}  // namespace
}  // namespace hmb::test
