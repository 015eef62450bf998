#include "hmblur/device_profile.h"

#include <algorithm>
#include <cstdlib>
#include <cstdio>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/bvh/bvh_build_layout.h"
#include "kernels/bvh/treelet_build_layout.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/shared/dispatch.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"

namespace hmb::vk {

const char* deviceProfileChoiceName(DeviceProfileChoice choice) {
  switch (choice) {
    case DeviceProfileChoice::Auto: return "auto";
    case DeviceProfileChoice::Cpu: return "cpu";
    case DeviceProfileChoice::Gpu: return "gpu";
  }
  return "";
}

DeviceProfileChoice parseDeviceProfileChoice(std::string_view text) {
  for (const DeviceProfileChoice choice : {DeviceProfileChoice::Auto, DeviceProfileChoice::Cpu, DeviceProfileChoice::Gpu})
    if (text == deviceProfileChoiceName(choice)) return choice;
  throw Error("device profile '" + std::string(text) + "': expected auto, cpu or gpu");
}

DeviceProfileChoice deviceProfileChoiceFromEnvironment() {
  const char* value = std::getenv("HMB_DEVICE_PROFILE");
  if (!value || !*value) return DeviceProfileChoice::Auto;
  try {
    return parseDeviceProfileChoice(value);
  } catch (const Error& error) {
    throw Error(std::string("HMB_DEVICE_PROFILE: ") + error.what());
  }
}

bool isLavapipeBefore23(const DeviceInfo& device) {
  // driverInfo reads "Mesa 22.3.6 (LLVM 15.0.6)"; an unknown release is taken as the older.
  if (device.driverName != "llvmpipe") return false;
  int major = 0;
  return std::sscanf(device.driverInfo.c_str(), "Mesa %d", &major) != 1 || major < 23;
}

DeviceProfileChoice deviceProfileChoiceOrEnvironment(std::string_view given) {
  return given.empty() ? deviceProfileChoiceFromEnvironment() : parseDeviceProfileChoice(given);
}

std::optional<uint32_t> driverLoopBudget(const DeviceInfo& device) {
  // Mesa 23 lifted the limit.
  return isLavapipeBefore23(device) ? std::optional<uint32_t>(HMB_LOOP_BUDGET) : std::nullopt;
}

DeviceProfile makeDeviceProfile(const DeviceInfo& device, uint32_t maxWorkGroupSizeX, uint32_t maxWorkGroupInvocations,
                                DeviceProfileChoice choice) {
  DeviceProfile profile;
  profile.forced = choice != DeviceProfileChoice::Auto;
  const bool cpu = choice == DeviceProfileChoice::Auto ? device.type == "cpu" : choice == DeviceProfileChoice::Cpu;
  profile.name = cpu ? "cpu" : "gpu";
  profile.loopBudget = driverLoopBudget(device);
  profile.uniformAtomicRounds = isLavapipeBefore23(device);
  profile.rasterTileLists = cpu;
  if (cpu) {
    profile.bvhLevelGroup = HMB_BVH_LEVEL_GROUP;
    profile.bvhLaneBins = true;
    profile.topLevelSmallTask = HMB_BVH_TOP_LEVEL_SMALL_TASK_CPU;
    profile.rangeCheckGroups = HMB_RANGE_CHECK_CPU_GROUPS;
    profile.shutterListGroups = HMB_SHUTTER_LIST_CPU_GROUPS;
  } else {
    // A warp or a wave (32 to 64 lanes) within the device's workgroup limits.
    profile.bvhLevelGroup = std::min({std::clamp(device.subgroupSize, 32u, 64u), maxWorkGroupSizeX, maxWorkGroupInvocations});
    profile.bvhLaneBins = false;
    profile.topLevelSmallTask = HMB_BVH_SMALL_TASK;
    profile.linearTopLevel = true;
    // Its sort's groups take a lane per digit; a device that allows fewer keeps the binned builder.
    profile.treeletMeshBuilds = maxWorkGroupSizeX >= HMB_TREELET_SORT_GROUP &&
                                maxWorkGroupInvocations >= HMB_TREELET_SORT_GROUP;
    profile.gatherSkipsRayMask = true;
    profile.edgeCandidatesInTileMax = true;
  }
  return profile;
}

std::string DeviceProfile::describe() const {
  std::string line = name + (forced ? " (forced)" : "") + ": raster " + (rasterTileLists ? "tile lists" : "atomics") +
                     ", bvh levels of " + std::to_string(bvhLevelGroup) + " lanes " +
                     (bvhLaneBins ? "with per-lane bins" : "with shared atomics") + ", top-level small tasks of " +
                     std::to_string(topLevelSmallTask) + (linearTopLevel ? ", a linear top level" : "") +
                     (treeletMeshBuilds ? ", treelet mesh builds" : "") + ", gather " +
                     (gatherSkipsRayMask ? "skips the ray mask" : "over every pixel") + ", list walks in " +
                     (rangeCheckGroups == 0 ? std::string("a group per block") : std::to_string(rangeCheckGroups) + " groups");
  line += loopBudget ? ", loop budget " + std::to_string(*loopBudget) + " rounds an invocation" : ", no loop budget";
  if (uniformAtomicRounds) line += ", atomic loops kept uniform";
  return line;
}

}  // namespace hmb::vk
