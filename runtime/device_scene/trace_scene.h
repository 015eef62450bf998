// The scene as the ray tracing kernels see it (kernels/trace/trace_layout.h): every mesh's
// triangles in its own space under a BVH per mesh, built on the device once; and the instances
// at a frame's shutter times under a top-level BVH over their motion bounds, rebuilt on the
// device whenever an instance's transform at those times changes. A renderer keeps one trace
// scene across frames: its mesh trees serve every frame of the same meshes, and its top
// level every frame in which no instance moved; where most stand still and a few move, the
// top level's tree over the still ones serves too, and the moving ones are inserted into it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/buffer.h"
#include "hmblur/scene.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/passes/bvh_build_pass.h"
#include "runtime/passes/linear_bvh_pass.h"
#include "runtime/vulkan/buffer_group.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb::vk {
class FrameRecorder;
struct FrameTimings;
}

namespace hmb {

class FramePlan;
class GpuScene;

// The camera at time t as rays (kernels/trace/trace_layout.h): the same pinhole the
// rasterizer projects with, so a ray through a pixel centre meets what the raster sees there.
gpu::PinholeCamera pinholeCamera(const scene::Scene& scene, float t, uint32_t width, uint32_t height);

// FNV-1a over 32-bit words of what the meshes' trees depend on (positions and triangles), so a
// change to any of them gives another fingerprint.
uint64_t meshFingerprint(const scene::Scene& scene);

class TraceScene {
 public:
  static constexpr const char* kTriangleBounds = "bvh-triangle-bounds";
  static constexpr const char* kDeformedLeaves = "bvh-deformed-leaves";
  static constexpr const char* kRefit = "bvh-refit";
  static constexpr const char* kInstanceTree = "bvh-instance-tree";  // setShutterTimes' passes
  static constexpr const char* kStillInstanceTree = "bvh-still-instance-tree";  // buildStillInstanceTree's

  // Where at least `stillInstances` instances stand still (no animation above their node, no
  // deformation) and a few others move (at most HMB_BVH_MAX_INSERTED), the top level is split:
  // the still ones' tree is kept from frame to frame while they stay as they are, and the
  // moving ones are inserted into it again in each (passes::BvhBuildPass::recordKeptWithInsertions).
  // 0 (the default) builds one tree over all in every frame.
  void splitTopLevel(uint32_t stillInstances) { splitFrom_ = stillInstances; }
  // The fewest still instances for which a renderer splits. On a CPU device one invocation
  // builds the top level, in time growing as n log n, where the insertions are one dispatch,
  // which costs the traces a little (the moving ones sit where they were inserted, not where a
  // build would put them): bench/results/top-level-insertion/. On a GPU the levels of a build
  // cost most of bistro's top level (bench/results/nvidia-h200/), where the insertions are one
  // workgroup's walks down some 15 levels each (not measured on a GPU).
  static constexpr uint32_t kStillInstancesToSplit = 128;
  // The instances in the split's order, the still ones first, and how many are still.
  static std::pair<std::vector<uint32_t>, uint32_t> stillFirstOrder(const scene::Scene& scene);
  // Why `scene`'s top level is not split at that threshold (empty: it is).
  static std::string whyNotSplit(const scene::Scene& scene, uint32_t stillInstances);

  // The meshes' trees: every mesh's triangles in its own space under a BVH per mesh, and the
  // triangles' vertices in the leaves' order. Trace scenes may share them (frames in flight,
  // each with a top level of its own) while no mesh deforms: a refit changes them in place.
  struct MeshTrees {
    // Uploads the meshes and builds their trees (submits on `frame`).
    MeshTrees(const vk::Context& context, const scene::Scene& scene, vk::FrameRecorder& frame,
              const passes::BvhBuildShape& meshShape);
    // Whether they were built from meshes with the same positions and triangles as `scene`'s
    // (a 64-bit fingerprint of them).
    bool serves(const scene::Scene& scene) const;

    passes::BvhBuildPass bvh;
    vk::Buffer leafTriangles;  // per triangle in the leaves' order: 3 vec4 (vertex xyz, index bits)
    uint32_t meshCount = 0;
    uint32_t triangleCount = 0;
    std::vector<uint32_t> firstTriangle;  // each mesh's first triangle
    uint64_t fingerprint = 0;
  };

  // Uploads the meshes and builds their trees (submits on `frame`), with the profile's mesh
  // builder or, where given, in `meshShape` (benchmarks and tests compare the builders).
  TraceScene(const vk::Context& context, const scene::Scene& scene, vk::FrameRecorder& frame);
  TraceScene(const vk::Context& context, const scene::Scene& scene, vk::FrameRecorder& frame,
             const passes::BvhBuildShape& meshShape);
  // A trace scene over trees another built, with a top level of its own.
  TraceScene(const vk::Context& context, std::shared_ptr<MeshTrees> meshes);
  const std::shared_ptr<MeshTrees>& meshTrees() const { return meshes_; }

  // Transforms of every instance at each shutter time, and the top level over the instances'
  // boxes merged over those times (submits on `frame` and waits). Rays name a time by its
  // index here.
  void setShutterTimes(const scene::Scene& scene, std::span<const float> times, vk::FrameRecorder& frame);
  // The same in two steps, for a frame that must not wait (an engine's): stageShutterTimes
  // computes the transforms on the host and sizes the buffers; recordStagedShutterTimes
  // records their upload (through the command buffer), the instances' motion bounds and the
  // top level's build into a begun frame, every pass under the name `pass`, with no
  // submission and no read-back (passes::BvhBuildPass::record). Tracing kernels recorded after
  // it in the same frame see the new tree. The staged transforms stay until the next staging,
  // so a frame recorded again (or after a failed recording) builds the same tree.
  void stageShutterTimes(const scene::Scene& scene, std::span<const float> times);
  void recordStagedShutterTimes(vk::FrameRecorder& frame, std::string_view pass);

  // A scene with skinned or morphing meshes: deforms `gpuScene`'s vertices to time t, takes the
  // deforming meshes' trace triangles from them and refits those meshes' trees to their new
  // boxes (topology kept; the trees were built over the rest pose). Static meshes' trees are
  // left as they are. Call setShutterTimes after it: the instances' boxes
  // changed. Returns the device times of the three steps (DeformedVertices::kName,
  // kDeformedLeaves, kRefit).
  vk::FrameTimings followDeformation(const scene::Scene& scene, float t, GpuScene& gpuScene, vk::FrameRecorder& frame);
  // The same in two steps, for a frame that must not wait (an engine's): prepareRefit does the
  // host's part (which meshes deform; the first refit's round trip, on `setup`, waited for)
  // and returns the device milliseconds it waited for; recordRefit records, into a begun
  // frame whose earlier passes put `gpuScene`'s vertices at the time wanted
  // (GpuScene::recordFrameDeformation), the deforming meshes' new leaves and their trees'
  // refit. The top level is then built again.
  double prepareRefit(const scene::Scene& scene, vk::FrameRecorder& setup);
  void recordRefit(const GpuScene& gpuScene, vk::FrameRecorder& frame);

  // Whether this trace scene was built from meshes with the same positions and triangles as
  // `scene`'s (a 64-bit fingerprint of them), so its mesh trees serve that scene.
  bool hasMeshesOf(const scene::Scene& scene) const;
  // Whether the top level was last built for the same instances with the same transforms at
  // each of these shutter times, so setShutterTimes would rebuild the same tree.
  bool hasShutterTimes(const scene::Scene& scene, std::span<const float> times) const;

  // The staged shutter times insert the moving instances into the top level alone: the still
  // ones' tree, built for an earlier frame, serves them.
  bool keepsStillInstanceTree() const { return keepsStillTree_; }
  // Whether a split build of `scene`'s still instances as they are now was recorded (so a
  // frame of it keeps their tree).
  bool hasStillInstanceTreeOf(const scene::Scene& scene) const;
  // Builds the staged split top level now (submits on `frame` and waits), so that the frames
  // recorded from this staging only insert the moving instances: a renderer's scene setup, as
  // the mesh trees are. Returns the device milliseconds.
  double buildStillInstanceTree(vk::FrameRecorder& frame);

  uint32_t meshCount() const { return meshes_->meshCount; }
  uint32_t instanceCount() const { return instanceCount_; }
  uint32_t timeCount() const { return timeCount_; }
  uint32_t triangleCount() const { return meshes_->triangleCount; }
  // The first triangle of each mesh in the triangle buffer: a hit's triangle minus its
  // mesh's first is the triangle's index in scene::Mesh::indices / 3.
  const std::vector<uint32_t>& meshFirstTriangle() const { return meshes_->firstTriangle; }

  const passes::BvhBuildPass& meshBvh() const { return meshes_->bvh; }
  // The binned builder of the top level (a split top level's insertions are its): the tree
  // traversal reads unless the last build was the linear one (vk::DeviceProfile::linearTopLevel).
  const passes::BvhBuildPass& instanceBvh() const { return instanceBvh_; }
  bool linearTopLevel() const { return linearTopLevel_; }
  // The last top level was split: the moving instances inserted into the still ones' tree.
  bool topLevelHasInsertions() const { return !linearTopLevel_ && instanceBvh_.hasInsertions(); }
  // The top level as the last build left it, whichever builder made it: the tree (rooted at
  // node 0, primitive indices the instances') and every node as indexed on the device (tests).
  bvh::Bvh downloadInstanceTree() const;
  std::vector<gpu::BvhNode> downloadInstanceNodes() const;
  // The device time of the top level's last build by setShutterTimes.
  double instanceTreeMilliseconds() const { return instanceTreeMilliseconds_; }
  // 3 vec4 per triangle in the leaves' order (BvhHit::entry): its vertices, their indices in w.
  const vk::Buffer& leafTriangles() const { return meshes_->leafTriangles; }
  const vk::Buffer& instances() const { return instances_; }
  const vk::Buffer& transforms() const { return transforms_; }
  const vk::Buffer& instanceBoxes() const { return instanceBoxes_; }
  // Binds the trace scene as a tracing kernel declares it (kernels/trace/trace_scene_bindings.glsl)
  // from firstBinding on: its 10 buffers, or the table of their addresses for a kernel that binds
  // by address.
  void bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const;
  // The traces' status: the traces the driver's loop limit cut short
  // (kernels/trace/closest_hit.glsl) since the last reset, which a render makes before its
  // traces (at once, or recorded in the frame as pass `pass` where nothing may wait), and reads
  // after them.
  void resetStatus();
  void recordResetStatus(vk::FrameRecorder& frame, std::string_view pass) const;
  uint32_t cutTraces() const;

 private:
  // The instances' motion bounds and the top level's build, from the transforms on the device.
  void recordInstanceTree(vk::FrameRecorder& frame, std::string_view pass);
  // The staged instances and transforms uploaded and their tree built, waited for; returns the
  // device milliseconds.
  double buildStagedTree(vk::FrameRecorder& frame, std::string_view pass);

  const vk::Context& context_;
  vk::ComputeKernel motionBoundsKernel_;
  vk::ComputeKernel deformedLeavesKernel_;
  std::shared_ptr<MeshTrees> meshes_;
  passes::BvhBuildPass instanceBvh_;
  passes::LinearBvhPass linearInstanceBvh_;
  bool linearTopLevel_ = false;  // the last top level recorded was the linear builder's
  double instanceTreeMilliseconds_ = 0.0;
  uint32_t instanceCount_ = 0;
  uint32_t timeCount_ = 0;
  // What the top level was last built from, to tell whether a frame can keep it.
  std::vector<gpu::TraceInstance> builtInstances_;
  std::vector<gpu::InstanceTransform> builtTransforms_;
  bool treeRecorded_ = false;  // a build of the staged instances was recorded (or built)
  // The top level's split (splitTopLevel): the instances, still ones first (empty: one tree
  // over all), how many are still, and the still ones' records and transforms (the same at
  // every time), which their tree is built from.
  struct StillPart {
    std::vector<uint32_t> order;
    uint32_t count = 0;
    std::vector<gpu::TraceInstance> instances;
    std::vector<gpu::InstanceTransform> transforms;
  };
  static StillPart stillPartOf(const scene::Scene& scene);
  // Whether the still tree last recorded was built from `part`.
  bool servesStill(const StillPart& part) const;
  StillPart still_;  // the staged frame's (empty order: not split)
  uint32_t splitFrom_ = 0;  // splitTopLevel
  // keepsStillTree_: the staged frame inserts the moving ones into the kept tree alone.
  bool stillTreeRecorded_ = false;
  bool keepsStillTree_ = false;
  vk::Buffer instances_;      // TraceInstance per instance
  vk::Buffer transforms_;     // InstanceTransform per (instance, time)
  vk::Buffer instanceBoxes_;  // BvhBox per instance: its motion bounds
  vk::Buffer deformedBoxes_;  // BvhBox per triangle, for refits (deforming scenes only)
  std::vector<glm::uvec3> deformedMeshes_;  // prepareRefit's: (mesh, first triangle, triangles)
  vk::Buffer status_;         // HMB_TRACE_STATUS_WORDS uint, written by the traces
  vk::BufferGroup group_;     // the buffers above, as tracing kernels bind them
};

// The mesh trees several trace scenes share (frames in flight: passes::HybridStage::shareMeshTrees):
// the last ones a sharing stage built, empty until one does.
struct SharedMeshTrees {
  std::shared_ptr<TraceScene::MeshTrees> trees;
};

// The trace scene a stage keeps from one frame to the next (the hybrid's, the reference's).
// planKeptMeshTrees enters the stage's mesh-tree build `buildPass` in the plan, skipped when
// `kept` has the scene's meshes, and returns whether it has. prepareKeptMeshTrees builds
// `kept` afresh when the plan runs `buildPass` (the old trees go first: the two never take
// memory at once) and returns the build's device milliseconds, nullopt when the kept serve.
// Enters TraceScene::followDeformation's passes in the plan: run for a scene with deforming
// meshes, skipped (with the reason) for one without.
void planDeformedTrees(FramePlan& plan, const scene::Scene& scene);
bool planKeptMeshTrees(FramePlan& plan, std::string_view buildPass, const TraceScene* kept, const scene::Scene& scene);
std::optional<double> prepareKeptMeshTrees(std::unique_ptr<TraceScene>& kept, std::string_view buildPass,
                                           const FramePlan& plan, const vk::Context& context, const scene::Scene& scene,
                                           vk::FrameRecorder& frame);

}  // namespace hmb
