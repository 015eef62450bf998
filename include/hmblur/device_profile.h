// Every choice that differs between a CPU device (lavapipe) and a GPU, made once from the
// device's properties and named, so no pass asks what kind of device it runs on. A profile can
// be forced (`--device-profile cpu|gpu`), so that a GPU's choices run, and are tested, on
// lavapipe. What the driver itself imposes (its loop budget) is a fact of the device, which no
// forced profile changes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace hmb::vk {

struct DeviceInfo;

enum class DeviceProfileChoice {
  Auto,  // from the device's type: "cpu" for CPU devices, "gpu" for every other
  Cpu,
  Gpu,
};

// "auto", "cpu", "gpu"; the parse throws hmb::Error naming the accepted values.
const char* deviceProfileChoiceName(DeviceProfileChoice choice);
DeviceProfileChoice parseDeviceProfileChoice(std::string_view text);
// HMB_DEVICE_PROFILE from the environment (auto where unset): the default of the CLI, the
// benchmarks and the test fixture, so a whole test run can force a profile.
DeviceProfileChoice deviceProfileChoiceFromEnvironment();
// A front end's --device-profile: the text given, or the environment's where none was given.
DeviceProfileChoice deviceProfileChoiceOrEnvironment(std::string_view given);

struct DeviceProfile {
  std::string name;     // "cpu" or "gpu": whose choices these are
  bool forced = false;  // chosen by the user, not from the device's type

  // Facts of the driver, the same under any forced profile.
  // Mesa 22.3's lavapipe ends every loop of an invocation after 65535 rounds in all, silently;
  // kernels whose loops could pass it are sized to stay within this many (empty: no budget).
  std::optional<uint32_t> loopBudget;
  // Mesa 22.3's lavapipe returned wrong values from atomics to the lanes of a vector some of
  // whose lanes had left a loop: kernels that count arrivals with atomics in a loop keep every
  // lane in it to the loop's last round (kernels/bvh/linear_bounds.comp), which a GPU need not.
  bool uniformAtomicRounds = false;

  // The G-buffer rasterizer: per-tile triangle lists walked by one invocation a tile (a CPU
  // runs a tile's pixels as vector code and can skip per-pixel atomics), else a visibility
  // buffer written with atomics (passes::defaultVisibilityScheme).
  bool rasterTileLists = false;
  // The BVH builder's level workgroups: lanes per group, and whether large tasks bin into
  // per-lane copies of the bins (a CPU's 8 lanes) or with shared atomics (a GPU's warp).
  uint32_t bvhLevelGroup = 0;
  bool bvhLaneBins = false;
  // The largest top-level tree one invocation builds whole, with no level (on a CPU the top
  // level over a few hundred instances is cheaper as one lane's work than as levels).
  uint32_t topLevelSmallTask = 0;
  // The per-frame top level over the instances is built by the linear builder (Morton codes,
  // one workgroup's sort, a Karras hierarchy: passes::LinearBvhPass), in a constant four
  // dispatches, where the binned SAH builder records two a level (a GPU pays a launch and drain
  // for each; a CPU device's lane builds a few hundred instances' tree whole in one).
  bool linearTopLevel = false;
  // Mesh trees are built by the treelet builder (Morton codes, a radix sort, a Karras tree
  // improved by treelets on the way up: passes::TreeletBuild) in a constant nine dispatches with
  // no host wait, where the binned SAH builder records two a level and waits between batches
  // of levels; on a CPU device the binned builder is faster and its trees a little cheaper.
  bool treeletMeshBuilds = false;
  // The hybrid's post-process gather leaves the ray mask's pixels out (a GPU's warp wholly in
  // the mask skips its samples; a CPU runs every lane of a vector and pays for the mask's load).
  bool gatherSkipsRayMask = false;
  // The hybrid's edge candidates are found inside the tile-max's loop on every frame, where a
  // CPU device finds them there only when the camera moves on screen (else in their own pass).
  bool edgeCandidatesInTileMax = false;
  // Groups of the hybrid's list walks (the range check, the shutter rays' list): 0 for one
  // group per listed block (a GPU), else this many groups in all, each a run of blocks (enough
  // to keep a CPU's threads busy without paying a group's overhead per block).
  uint32_t rangeCheckGroups = 0;
  uint32_t shutterListGroups = 0;

  // One line for reports and `hmblur list-devices`.
  std::string describe() const;
};

// The profile of a device: the one its type asks for, or the one forced.
DeviceProfile makeDeviceProfile(const DeviceInfo& device, uint32_t maxWorkGroupSizeX, uint32_t maxWorkGroupInvocations,
                                DeviceProfileChoice choice);

// The loop budget of a driver: lavapipe before Mesa 23 has one (DeviceProfile::loopBudget).
std::optional<uint32_t> driverLoopBudget(const DeviceInfo& device);
// Lavapipe of a Mesa release before 23 (or of an unknown one): its loop budget, its atomics.
bool isLavapipeBefore23(const DeviceInfo& device);

}  // namespace hmb::vk
