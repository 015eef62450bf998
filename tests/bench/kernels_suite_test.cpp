// hmblur-bench's kernels suite and its --suite spelling, run as a user runs them, at tiny sizes.
// Every command runs with --validation, so a validation error fails it with exit code 3.
// Times are only checked to be measured (positive), never against a threshold.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/bench/bench_harness.h"

namespace hmb::test {
namespace {

namespace fs = std::filesystem;

// (kernel, width, height, triangles, rays) of every case in a report.
using CaseKey = std::tuple<std::string, uint32_t, uint32_t, uint32_t, uint32_t>;

std::multiset<CaseKey> caseKeys(const nlohmann::json& report) {
  std::multiset<CaseKey> keys;
  for (const nlohmann::json& c : report.at("cases"))
    keys.emplace(c.at("kernel"), c.at("width"), c.at("height"), c.at("triangles"), c.at("rays"));
  return keys;
}

// Every case timed `repeats` times, each time positive, and a positive throughput of what it counts.
void expectMeasured(const nlohmann::json& report, size_t repeats) {
  for (const nlohmann::json& c : report.at("cases")) {
    const std::string what = c.dump();
    const std::string kernel = c.at("kernel");
    ASSERT_EQ(c.at("ms").at("samples").size(), repeats) << what;
    for (double ms : c.at("ms").at("samples")) EXPECT_GT(ms, 0.0) << what;
    EXPECT_GT(c.at("ms").at("median").get<double>(), 0.0) << what;
    EXPECT_GT(c.at("throughput").get<double>(), 0.0) << what;
    EXPECT_FALSE(c.at("passes").empty()) << what;
    const uint64_t pixels = c.at("width").get<uint64_t>() * c.at("height").get<uint64_t>();
    if (kernel == "raster" || kernel == "bvh-build") {
      EXPECT_EQ(c.at("items"), c.at("triangles")) << what;
      EXPECT_EQ(c.at("throughput_unit"), "Mtris/s") << what;
    } else if (kernel == "trace") {
      EXPECT_EQ(c.at("items"), c.at("rays")) << what;
      EXPECT_EQ(c.at("throughput_unit"), "Mrays/s") << what;
    } else {
      EXPECT_EQ(c.at("items"), pixels) << what;
      EXPECT_EQ(c.at("throughput_unit"), "Mpixels/s") << what;
    }
  }
}

TEST(KernelsSuite, TimesEveryKernelAtEveryRequestedSize) {
  const fs::path dir = tempDir("bench_kernels");
  const std::string out = (dir / "kernels.json").string();
  const CliRun run =
      bench("kernels --sizes 64x64,40x24 --triangles 300,200 --rays 500,300 --warmup 1 --repeats 2 --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;

  const nlohmann::json report = readJson(dir / "kernels.json");
  EXPECT_EQ(report.at("suite"), "kernels");
  for (const char* field : {"what", "command", "date", "device", "system"})
    EXPECT_TRUE(report.contains(field)) << field;
  EXPECT_EQ(report.at("settings").at("repeats"), 2);
  const std::multiset<CaseKey> expected = {
      {"raster", 64, 64, 300, 0},  {"raster", 64, 64, 200, 0},  {"raster", 40, 24, 300, 0}, {"raster", 40, 24, 200, 0},
      {"bvh-build", 0, 0, 300, 0}, {"bvh-build", 0, 0, 200, 0}, {"trace", 0, 0, 300, 500},  {"trace", 0, 0, 300, 300},
      {"trace", 0, 0, 200, 500},   {"trace", 0, 0, 200, 300},   {"tile-max", 64, 64, 0, 0}, {"tile-max", 40, 24, 0, 0},
      {"gather", 64, 64, 0, 0},    {"gather", 40, 24, 0, 0}};
  EXPECT_EQ(caseKeys(report), expected);
  expectMeasured(report, 2);

  // What each kernel did: the work was there to time.
  for (const nlohmann::json& c : report.at("cases")) {
    const nlohmann::json& details = c.at("details");
    if (c.at("kernel") == "raster") {
      EXPECT_GT(details.at("setup_triangles"), 0u) << c.dump();
      EXPECT_LE(details.at("setup_triangles"), c.at("triangles")) << c.dump();
    } else if (c.at("kernel") == "bvh-build") {
      EXPECT_GT(details.at("leaves"), 0u) << c.dump();
    } else if (c.at("kernel") == "trace") {
      EXPECT_GT(details.at("hits"), 0u) << c.dump();
      EXPECT_LE(details.at("hits"), c.at("rays")) << c.dump();
    }
  }

  // The CSV (a header and a row per case) and the Markdown table beside the JSON.
  std::ifstream csv(dir / "kernels.csv");
  std::string line;
  size_t rows = 0;
  ASSERT_TRUE(std::getline(csv, line));
  EXPECT_EQ(line.rfind("kernel,width,height,triangles,rays,median_ms", 0), 0u) << line;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, expected.size());
  std::ifstream markdown(dir / "kernels.md");
  std::stringstream table;
  table << markdown.rdbuf();
  for (const char* kernel : {"| raster |", "| bvh-build |", "| trace |", "| tile-max |", "| gather |"})
    EXPECT_NE(table.str().find(kernel), std::string::npos) << kernel;
}

// The spelling, --suite NAME --repeat N, runs the same suite; a kernel named like a
// suite (raster) stays a value of --kernels.
TEST(KernelsSuite, SuiteOptionSelectsTheSuiteWithItsOptions) {
  const fs::path dir = tempDir("bench_suite_option");
  const std::string out = (dir / "kernels.json").string();
  const CliRun run = bench(
      "--suite kernels --kernels raster,tile-max --sizes 32x32 --triangles 100 --warmup 0 --repeat 1 --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(dir / "kernels.json");
  EXPECT_EQ(report.at("suite"), "kernels");
  EXPECT_EQ(report.at("settings").at("repeats"), 1);
  EXPECT_EQ(caseKeys(report), (std::multiset<CaseKey>{{"raster", 32, 32, 100, 0}, {"tile-max", 32, 32, 0, 0}}));
  expectMeasured(report, 1);
}

TEST(KernelsSuite, SceneIsAnAliasOfScenes) {
  const fs::path dir = tempDir("bench_scene_alias");
  const std::string out = (dir / "passes.json").string();
  const CliRun run =
      bench("--suite passes --scene living-room --sizes 32x18 --methods sharp --warmup 0 --repeat 1 --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(dir / "passes.json");
  EXPECT_EQ(report.at("suite"), "passes");
  ASSERT_EQ(report.at("cases").size(), 1u);
  EXPECT_EQ(report.at("cases").at(0).at("scene"), "living-room");
  EXPECT_EQ(report.at("cases").at(0).at("frame_ms").at("samples").size(), 1u);
}

// The passes suite gives each method's frame shape beside its times, in the JSON and in the
// table it prints, under the profile forced.
TEST(KernelsSuite, PassesGivesEachMethodsFrameShape) {
  const fs::path dir = tempDir("bench_passes_shape");
  const std::string out = (dir / "passes.json").string();
  const CliRun run = runProgram(HMB_BENCH_PATH, "--validation --device-profile gpu passes --scene temple --sizes 64x36 "
                                               "--methods postprocess,hybrid --warmup 0 --repeat 1 "
                                               "--out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_NE(run.output.find("| dispatches (indirect) | barriers | host waits | dependent chain |"), std::string::npos)
      << run.output;
  const nlohmann::json report = readJson(out);
  EXPECT_EQ(report.at("device").at("profile").at("name"), "gpu");
  ASSERT_EQ(report.at("cases").size(), 2u);
  for (const nlohmann::json& c : report.at("cases")) {
    const nlohmann::json& frame = c.at("frame");
    EXPECT_GT(frame.at("dispatches").get<int>(), 5) << c.dump();
    EXPECT_EQ(frame.at("host_waits"), 1) << c.dump();
    EXPECT_LE(frame.at("dependent_chain").get<int>(), frame.at("dispatches").get<int>()) << c.dump();
  }
  EXPECT_GT(report.at("cases").at(1).at("frame").at("dispatches").get<int>(),
            report.at("cases").at(0).at("frame").at("dispatches").get<int>());
}

// Without --out a suite writes under out/bench/ of the working folder, never into the
// committed bench/results/.
TEST(KernelsSuite, ResultsGoUnderOutBenchUnlessToldOtherwise) {
  const fs::path dir = tempDir("bench_default_out");
  fs::create_directories(dir / "bench" / "results");
  const CliRun run = runProgram("cd " + dir.string() + " && " + std::string(HMB_BENCH_PATH),
                                "--validation --quiet kernels --kernels tile-max --sizes 32x32 --warmup 0 --repeat 1");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "bench" / "kernels" / "kernels.json"));
  EXPECT_TRUE(fs::is_empty(dir / "bench" / "results"));
}

TEST(KernelsSuite, UnknownSuiteOrOptionFails) {
  expectOneLineError(bench("--suite nosuch --repeat 1"), "unknown suite 'nosuch'");
  const CliRun unknownOption = bench("--suite kernels --no-such-option 1 --out ''");
  EXPECT_NE(unknownOption.exitCode, 0) << unknownOption.output;
  EXPECT_NE(unknownOption.output.find("--no-such-option"), std::string::npos) << unknownOption.output;
  const CliRun unknownKernel = bench("kernels --kernels nosuch --out ''");
  EXPECT_NE(unknownKernel.exitCode, 0) << unknownKernel.output;
  EXPECT_NE(unknownKernel.output.find("nosuch"), std::string::npos) << unknownKernel.output;
}

// --drivers runs the same cases once per driver and puts them side by side; "default" twice is
// the installed driver twice, so the test needs no second driver.
TEST(KernelsSuite, DriversRunsTheSameKernelsOnEachDriverSideBySide) {
  const fs::path dir = tempDir("bench_drivers");
  const std::string out = (dir / "kernels.json").string();
  const CliRun run = bench("kernels --drivers default,default --kernels tile-max,trace --sizes 32x32 --triangles 100 "
                           "--rays 200 --warmup 0 --repeats 1 --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  const nlohmann::json report = readJson(out);
  ASSERT_EQ(report.at("drivers").size(), 2u);
  for (const nlohmann::json& driver : report.at("drivers")) {
    EXPECT_EQ(driver.at("driver"), "default");
    EXPECT_EQ(caseKeys(driver), (std::multiset<CaseKey>{{"tile-max", 32, 32, 0, 0}, {"trace", 0, 0, 100, 200}}));
  }
  ASSERT_EQ(report.at("cases").size(), 2u);
  for (const nlohmann::json& c : report.at("cases")) {
    ASSERT_EQ(c.at("median_ms").size(), 2u) << c.dump();
    for (double ms : c.at("median_ms")) EXPECT_GT(ms, 0.0) << c.dump();
    EXPECT_DOUBLE_EQ(c.at("over_first").at(0).get<double>(), 1.0) << c.dump();
    EXPECT_NEAR(c.at("over_first").at(1).get<double>(),
                c.at("median_ms").at(1).get<double>() / c.at("median_ms").at(0).get<double>(), 1e-9);
  }
  std::ifstream markdown(dir / "kernels.md");
  std::stringstream table;
  table << markdown.rdbuf();
  EXPECT_NE(table.str().find("| driver 2 / 1 |"), std::string::npos) << table.str();
}

// --driver-files takes an ICD manifest: the installed lavapipe's own gives the same device.
TEST(KernelsSuite, DriverFilesRunsOnTheManifestsDriver) {
  fs::path manifest;
  std::error_code error;
  for (const fs::directory_entry& e : fs::directory_iterator("/usr/share/vulkan/icd.d", error))
    if (e.path().filename().string().rfind("lvp_icd.", 0) == 0) manifest = e.path();
  if (manifest.empty()) GTEST_SKIP() << "no installed lavapipe manifest";
  const fs::path dir = tempDir("bench_driver_files");
  const std::string out = (dir / "kernels.json").string();
  const CliRun run = bench("--driver-files " + manifest.string() +
                           " kernels --kernels tile-max --sizes 32x32 --warmup 0 --repeats 1 --out " + out);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(readJson(out).at("device").at("driver"), "llvmpipe") << readJson(out).at("device").dump();
}

TEST(KernelsSuite, DriverFilesThatNameNoDriverFailInOneLine) {
  const fs::path dir = tempDir("bench_bad_driver_files");
  expectOneLineError(bench("--driver-files " + (dir / "missing").string() + " kernels --out ''"), "does not exist");
  std::ofstream(dir / "not-a-manifest.json") << "{\"file_format_version\": \"1.0.0\"}";
  expectOneLineError(bench("--driver-files " + (dir / "not-a-manifest.json").string() + " kernels --out ''"),
                     "no ICD.library_path");
  expectOneLineError(bench("--driver-files " + dir.string() + " kernels --out ''"), "no ICD.library_path");
  fs::create_directories(dir / "empty");
  expectOneLineError(bench("--driver-files " + (dir / "empty").string() + " kernels --out ''"), "holds no ICD manifest");
  expectOneLineError(bench("kernels --drivers default," + (dir / "missing").string() + " --out ''"), "does not exist");
}

}  // namespace
}  // namespace hmb::test
