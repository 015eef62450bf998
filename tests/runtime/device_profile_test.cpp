// The device profile: every choice that differs between a CPU device and a GPU, made once from
// the device and forced both ways here, so that a GPU's paths run (and are checked) on
// lavapipe. Each method renders the same image under either profile, within the bound below.
#include <algorithm>
#include <array>
#include <cstdlib>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "hmblur/context.h"
#include "hmblur/device_profile.h"
#include "hmblur/error.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "kernels/shared/dispatch.h"
#include "tests/support/display_psnr.h"

namespace hmb {
namespace {

// A context per forced profile, shared by the suite's tests and gone before the process ends
// (the validation layer's own state does not outlive main()).
class DeviceProfileTest : public ::testing::Test {
 public:
  static void TearDownTestSuite() {
    for (std::unique_ptr<vk::Context>& context : contexts()) context.reset();
  }

 protected:
  static vk::Context& forcedContext(vk::DeviceProfileChoice choice) {
    std::unique_ptr<vk::Context>& made = contexts()[static_cast<int>(choice)];
    if (!made) {
      vk::ContextOptions options;
      options.validation = true;
      options.deviceProfile = choice;
      made = std::make_unique<vk::Context>(options);
    }
    return *made;
  }

 private:
  static std::array<std::unique_ptr<vk::Context>, 3>& contexts() {
    static std::array<std::unique_ptr<vk::Context>, 3> made;
    return made;
  }
};

size_t differingPixels(const io::Rgba8Image& a, const io::Rgba8Image& b) {
  size_t n = 0;
  for (size_t p = 0; p * 4 < a.pixels.size(); ++p)
    n += !std::equal(a.pixels.begin() + 4 * p, a.pixels.begin() + 4 * p + 4, b.pixels.begin() + 4 * p);
  return n;
}

TEST_F(DeviceProfileTest, ChoicesAreNamedAndParsed) {
  for (const char* name : {"auto", "cpu", "gpu"})
    EXPECT_STREQ(vk::deviceProfileChoiceName(vk::parseDeviceProfileChoice(name)), name);
  try {
    vk::parseDeviceProfileChoice("fast");
    FAIL() << "a profile named fast was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("auto, cpu or gpu"), std::string::npos) << error.what();
  }
}

// A CPU device's choices and a GPU's, from the device's type or forced, whatever the device.
TEST_F(DeviceProfileTest, EachProfileMakesItsOwnChoices) {
  vk::DeviceInfo cpu;
  cpu.type = "cpu";
  cpu.subgroupSize = 8;
  vk::DeviceInfo gpu;
  gpu.type = "discrete-gpu";
  gpu.subgroupSize = 32;
  const vk::DeviceProfile cpuAuto = vk::makeDeviceProfile(cpu, 1024, 1024, vk::DeviceProfileChoice::Auto);
  const vk::DeviceProfile gpuAuto = vk::makeDeviceProfile(gpu, 1024, 1024, vk::DeviceProfileChoice::Auto);
  EXPECT_EQ(cpuAuto.name, "cpu");
  EXPECT_FALSE(cpuAuto.forced);
  EXPECT_TRUE(cpuAuto.rasterTileLists);
  EXPECT_TRUE(cpuAuto.bvhLaneBins);
  EXPECT_FALSE(cpuAuto.gatherSkipsRayMask);
  EXPECT_FALSE(cpuAuto.edgeCandidatesInTileMax);
  EXPECT_GT(cpuAuto.rangeCheckGroups, 0u);
  EXPECT_GT(cpuAuto.shutterListGroups, 0u);
  EXPECT_GT(cpuAuto.topLevelSmallTask, gpuAuto.topLevelSmallTask);
  EXPECT_EQ(gpuAuto.name, "gpu");
  EXPECT_FALSE(gpuAuto.rasterTileLists);
  EXPECT_FALSE(gpuAuto.bvhLaneBins);
  EXPECT_EQ(gpuAuto.bvhLevelGroup, 32u);
  EXPECT_TRUE(gpuAuto.gatherSkipsRayMask);
  EXPECT_TRUE(gpuAuto.edgeCandidatesInTileMax);
  EXPECT_TRUE(gpuAuto.linearTopLevel);
  EXPECT_FALSE(cpuAuto.linearTopLevel);
  EXPECT_TRUE(gpuAuto.treeletMeshBuilds);
  EXPECT_FALSE(cpuAuto.treeletMeshBuilds);
  EXPECT_EQ(gpuAuto.rangeCheckGroups, 0u);
  EXPECT_EQ(gpuAuto.shutterListGroups, 0u);
  // Forced, each device takes the other's choices.
  const vk::DeviceProfile cpuAsGpu = vk::makeDeviceProfile(cpu, 1024, 1024, vk::DeviceProfileChoice::Gpu);
  EXPECT_EQ(cpuAsGpu.name, "gpu");
  EXPECT_TRUE(cpuAsGpu.forced);
  EXPECT_FALSE(cpuAsGpu.rasterTileLists);
  EXPECT_EQ(cpuAsGpu.bvhLevelGroup, 32u);  // a warp's, whatever the CPU's vectors
  const vk::DeviceProfile gpuAsCpu = vk::makeDeviceProfile(gpu, 1024, 1024, vk::DeviceProfileChoice::Cpu);
  EXPECT_EQ(gpuAsCpu.name, "cpu");
  EXPECT_TRUE(gpuAsCpu.rasterTileLists);
  // A wave of 64, within a device that allows fewer invocations a group.
  gpu.subgroupSize = 64;
  EXPECT_EQ(vk::makeDeviceProfile(gpu, 1024, 1024, vk::DeviceProfileChoice::Auto).bvhLevelGroup, 64u);
  EXPECT_EQ(vk::makeDeviceProfile(gpu, 1024, 48, vk::DeviceProfileChoice::Auto).bvhLevelGroup, 48u);
  // The treelet builder's sort takes groups of HMB_TREELET_SORT_GROUP lanes, which Vulkan does not
  // promise (its minimum is 128): a device that allows fewer builds its meshes in levels.
  EXPECT_FALSE(vk::makeDeviceProfile(gpu, 128, 128, vk::DeviceProfileChoice::Auto).treeletMeshBuilds);
  EXPECT_TRUE(vk::makeDeviceProfile(gpu, 256, 256, vk::DeviceProfileChoice::Auto).treeletMeshBuilds);
}

// The driver's loop budget is a fact of the driver: lavapipe before Mesa 23 has one, under any
// profile; other drivers none. So is its atomics' defect in loops (uniformAtomicRounds).
TEST_F(DeviceProfileTest, TheLoopBudgetFollowsTheDriverNotTheProfile) {
  vk::DeviceInfo lavapipe;
  lavapipe.type = "cpu";
  lavapipe.driverName = "llvmpipe";
  lavapipe.driverInfo = "Mesa 22.3.6 (LLVM 15.0.6)";
  for (const auto choice : {vk::DeviceProfileChoice::Auto, vk::DeviceProfileChoice::Cpu, vk::DeviceProfileChoice::Gpu})
    EXPECT_EQ(vk::makeDeviceProfile(lavapipe, 1024, 1024, choice).loopBudget, std::optional<uint32_t>(HMB_LOOP_BUDGET));
  EXPECT_TRUE(vk::makeDeviceProfile(lavapipe, 1024, 1024, vk::DeviceProfileChoice::Gpu).uniformAtomicRounds);
  lavapipe.driverInfo = "Mesa 25.0.7-2~bpo12+1 (LLVM 19.1.7)";
  EXPECT_EQ(vk::driverLoopBudget(lavapipe), std::nullopt);
  EXPECT_FALSE(vk::isLavapipeBefore23(lavapipe));
  lavapipe.driverInfo = "an unknown build";
  EXPECT_EQ(vk::driverLoopBudget(lavapipe), std::optional<uint32_t>(HMB_LOOP_BUDGET)) << "unknown: stay within";
  vk::DeviceInfo nvidia;
  nvidia.type = "discrete-gpu";
  nvidia.driverName = "NVIDIA";
  nvidia.driverInfo = "560.35.03";
  EXPECT_EQ(vk::driverLoopBudget(nvidia), std::nullopt);
}

TEST_F(DeviceProfileTest, ForcedProfilesReachTheContext) {
  EXPECT_EQ(forcedContext(vk::DeviceProfileChoice::Cpu).profile().name, "cpu");
  EXPECT_TRUE(forcedContext(vk::DeviceProfileChoice::Cpu).profile().forced);
  EXPECT_EQ(forcedContext(vk::DeviceProfileChoice::Gpu).profile().name, "gpu");
  EXPECT_EQ(forcedContext(vk::DeviceProfileChoice::Cpu).profile().loopBudget,
            forcedContext(vk::DeviceProfileChoice::Gpu).profile().loopBudget);
}

struct ProfileCase {
  const char* scene;
  Method method;
  std::optional<uint32_t> rayBudget;  // hybrid-rays: rays a frame traces at most
};

// Every method under both profiles, forced, on the three reference scenes at 160x90: the
// rasterizer's visibility scheme, the BVH builder's shape and its top level's small tasks, the
// hybrid's gather, edge candidates and list walks all take the other side. The raster and the
// traces are exact (the nearest hit, ties to the lower id, whatever the tree's shape), so the
// images agree but for pixels whose hit is a tie between surfaces at one float distance: at
// most 0.1% of the pixels and 60 dB.
TEST_F(DeviceProfileTest, EveryMethodRendersTheSameImageUnderEitherProfile) {
  const ProfileCase cases[] = {
      {"living-room", Method::Sharp, std::nullopt},    {"living-room", Method::PostProcess, std::nullopt},
      {"living-room", Method::Hybrid, std::nullopt},   {"living-room", Method::HybridRays, std::nullopt},
      {"living-room", Method::Reference, std::nullopt}, {"temple", Method::Hybrid, std::nullopt},
      {"temple", Method::HybridRays, std::nullopt},    {"temple", Method::Reference, std::nullopt},
      {"bistro", Method::Hybrid, std::nullopt},        {"bistro", Method::HybridRays, std::nullopt},
      {"bistro", Method::HybridRays, 1000u},           {"bistro", Method::PostProcess, std::nullopt},
  };
  vk::Context& cpu = forcedContext(vk::DeviceProfileChoice::Cpu);
  vk::Context& gpu = forcedContext(vk::DeviceProfileChoice::Gpu);
  Renderer onCpu(cpu), onGpu(gpu);
  for (const ProfileCase& c : cases) {
    const scene::Scene scene = scene::loadScene(c.scene);
    RenderSettings settings;
    settings.method = c.method;
    settings.width = 160;
    settings.height = 90;
    settings.reference.samplesPerPixel = 16;
    settings.hybrid.rayBudget = c.rayBudget;
    const std::string what = std::string(c.scene) + " " + std::string(methodName(c.method)) +
                             (c.rayBudget ? " --ray-budget " + std::to_string(*c.rayBudget) : "");
    const RenderResult a = onCpu.render(scene, settings);
    const RenderResult b = onGpu.render(scene, settings);
    if (c.method != Method::Reference) {
      EXPECT_EQ(a.visibilityScheme, "tile-lists") << what;
      EXPECT_NE(b.visibilityScheme, "tile-lists") << what;
    }
    const size_t pixels = size_t(settings.width) * settings.height;
    EXPECT_LE(differingPixels(a.display, b.display), pixels / 1000) << what;
    EXPECT_GE(test::displayPsnr(a.display, b.display), 60.0) << what;
  }
  EXPECT_EQ(cpu.validationErrors(), 0u);
  EXPECT_EQ(gpu.validationErrors(), 0u);
}

// A frame's shape under the GPU profile: on a GPU every dispatch behind a barrier pays its
// launch and drain and every host wait a round trip, so the paper's hybrid may add at most 20
// dispatches to post-process's frame, and its frame is one submission the host waits for at
// its end (the trees kept across frames are scene setup, apart).
TEST_F(DeviceProfileTest, UnderTheGpuProfileThePapersHybridAddsFewDispatchesAndNoHostWait) {
  vk::Context& gpu = forcedContext(vk::DeviceProfileChoice::Gpu);
  Renderer renderer(gpu);
  for (const char* name : {"bistro", "temple", "living-room"}) {
    const scene::Scene scene = scene::loadScene(name);
    RenderSettings settings;
    settings.width = 1280;
    settings.height = 720;
    settings.method = Method::PostProcess;
    const RenderResult postprocess = renderer.render(scene, settings);
    settings.method = Method::Hybrid;
    const RenderResult hybrid = renderer.render(scene, settings);
    EXPECT_EQ(postprocess.frameShape.hostWaits, 1u) << name;
    EXPECT_EQ(hybrid.frameShape.submissions, 1u) << name;
    EXPECT_EQ(hybrid.frameShape.hostWaits, 1u) << name;
    EXPECT_LE(hybrid.frameShape.dispatches, postprocess.frameShape.dispatches + 20u) << name;
    EXPECT_GT(hybrid.frameShape.dispatches, postprocess.frameShape.dispatches) << name << ": the reveal's passes";
    EXPECT_LE(hybrid.frameShape.dependentChain, hybrid.frameShape.dispatches) << name;
  }
  EXPECT_EQ(gpu.validationErrors(), 0u);
}

}  // namespace
}  // namespace hmb
