// The `bvh` suite: the device BVH builder and trace kernel against the CPU full-sweep SAH
// build (quality) and Embree (speed) on the same triangles and rays, in one run on the same
// machine. Every scene is flattened to its world-space triangles at its frame time, so all
// sides build over the same primitives. Rays: coherent (one primary ray per pixel from the
// scene's camera) and incoherent (random origins in the scene's bounds, random directions).
// Every timed trace is also checked against Embree's hits (a fast wrong tracer is no result).
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/raster_suite.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb::vk {
class Context;
}

namespace hmb::bench {

// Below this fraction of rays on which the device and Embree agree (both miss, or hit at the
// same t within 1e-4 relative), the run fails; it fails as well on any ray where the device
// is wrong by the exact answer and grazes no edge (Disagreements).
constexpr double kMinHitAgreement = 0.999;

struct BvhSuiteOptions {
  std::vector<std::string> scenes;  // reference scene names, glTF paths, or "cube-sphere-1m"
  ImageSize coherentSize{640, 360};
  uint32_t incoherentRays = 230400;
  int warmup = 1;
  int repeats = 3;
  int embreeThreads = 0;  // 0: LP_NUM_THREADS when set, else every hardware thread
  // The driver's own acceleration structures and ray queries beside ours (ray_query_anchor.h),
  // where the device has them.
  bool rayQueryAnchor = true;
};

// The rays on which the device and Embree disagree, each judged by a double-precision brute
// force over every triangle: either passes within 1e-5 (barycentric) of an edge nearer than the
// farther answer (float tests may rightly differ there), or one of the two is wrong.
struct Disagreements {
  size_t rays = 0;
  size_t grazes = 0;
  size_t deviceWrong = 0;  // the run fails on any
  size_t embreeWrong = 0;
  std::string firstDeviceWrong;  // the first such ray, for the error
};

struct TraceFigures {
  uint32_t rays = 0;
  Summary deviceMilliseconds;
  Summary embreeMilliseconds;
  double deviceMraysPerSecond = 0, embreeMraysPerSecond = 0;
  double hitAgreement = 0;  // the last repeat's
  Disagreements disagreements;
  // The driver's ray queries (when measured), checked against Embree as the device is (against
  // the device where there is no Embree).
  Summary anchorMilliseconds;
  double anchorMraysPerSecond = 0;
  double anchorAgreement = 0;
  Disagreements anchorDisagreements;
};

struct BvhCase {
  std::string scene;
  uint32_t triangles = 0;
  Summary deviceBuildMilliseconds;  // triangle boxes + every level, device timestamps
  std::vector<double> deviceLevelMilliseconds;  // of the median build
  uint32_t deviceSmallTasks = 0;                // subtrees build_small_tasks finished
  double deviceSmallTaskMilliseconds = 0;       // its time in the median build
  Summary deviceRefitMilliseconds;              // refit of the built tree to its boxes, after the first
  double deviceFirstRefitMilliseconds = 0.0;    // the first, which prepares the others
  Summary setupWallMilliseconds;                // the trace scene's whole setup, host clock
  bool anchorMeasured = false;                  // the driver's ray queries ran (RayQueryAnchor)
  Summary anchorBuildMilliseconds;              // its bottom and top level builds
  uint32_t deviceLevels = 0;
  std::string deviceBuildShape;  // the level kernel's workgroups (passes::BvhBuildShape::describe)
  // What one build of the whole scene's tree asks of the device and the host: its dispatches,
  // barriers, submissions and host waits (vk::FrameShape), where a GPU pays a launch and drain
  // per dependent dispatch and a round trip per wait.
  vk::FrameShape deviceBuildFrame;
  Summary embreeSceneBuildMilliseconds;  // rtcCommitScene
  Summary embreeBvhBuildMilliseconds;    // rtcBuildBVH into our layout
  double cpuReferenceBuildMilliseconds = 0;  // full sweep, one thread
  double sahDevice = 0, sahReference = 0, sahEmbree = 0;
  TraceFigures coherent, incoherent;
  // The treelet builder (passes::TreeletBuild, the GPU profile's mesh builder) on the same
  // triangles, whatever the profile builds with: the whole setup's build (triangle boxes
  // included, as above), one build's shape, its tree's depth and SAH cost, and the same rays
  // traced through its tree, judged against Embree as the device's are.
  Summary treeletBuildMilliseconds;
  std::vector<std::pair<std::string, double>> treeletStageMilliseconds;  // of the median build, by stage
  vk::FrameShape treeletBuildFrame;
  uint32_t treeletLevels = 0;
  double sahTreelet = 0;
  TraceFigures treeletCoherent, treeletIncoherent;
  // The top-level tree over the scene's own instances (before it is flattened into one mesh),
  // built by the same builder with leaves of up to HMB_BVH_MAX_INSTANCE_LEAF instances, as the
  // hybrid and the reference build one each frame: where such a build's time goes. Not measured
  // for a scene of one instance (the frame leaves its top level out).
  uint32_t instances = 0;
  Summary topLevelMilliseconds;
  std::vector<double> topLevelLevelMilliseconds;  // of the median build
  uint32_t topLevelSmallTasks = 0;
  vk::FrameShape topLevelFrame;  // one build's (vk::FrameShape)
  double topLevelSmallTaskMilliseconds = 0;  // of the median build
  // Where the hybrid splits the top level (TraceScene::splitTopLevel): the moving instances
  // inserted into the still ones' kept tree, as each frame does (0 inserted: not split).
  uint32_t topLevelInserted = 0;
  Summary topLevelInsertionMilliseconds;
  // The same top level by the linear builder (passes::LinearBvhPass, the GPU profile's), recorded
  // and submitted as a frame records it: its time, its shape and its SAH cost over the binned one.
  Summary topLevelLinearMilliseconds;
  vk::FrameShape topLevelLinearFrame;
  double topLevelLinearSahOverBinned = 0.0;
};

// Why the suite leaves out the driver's ray queries on this context ("" when it runs them).
std::string rayQueryAnchorSkipped(const vk::Context& context, const BvhSuiteOptions& options);

std::vector<BvhCase> runBvhSuite(const vk::Context& context, const BvhSuiteOptions& options, const Progress& progress);
nlohmann::json bvhCaseJson(const BvhCase& c);
void printBvhTable(std::ostream& out, const std::vector<BvhCase>& cases);
int embreeThreadCount(int requested);

}  // namespace hmb::bench
