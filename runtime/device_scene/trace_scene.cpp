#include "runtime/device_scene/trace_scene.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>
#include <tuple>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/manifest.h"
#include "runtime/device_scene/deformed_vertices.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {

uint64_t meshFingerprint(const scene::Scene& scene) {
  uint64_t hash = 0xcbf29ce484222325ull;
  const auto mix = [&](uint32_t word) { hash = (hash ^ word) * 0x100000001b3ull; };
  mix(static_cast<uint32_t>(scene.meshes.size()));
  for (const scene::Mesh& mesh : scene.meshes) {
    mix(static_cast<uint32_t>(mesh.positions.size()));
    for (const glm::vec3& p : mesh.positions)
      for (int a = 0; a < 3; ++a) mix(std::bit_cast<uint32_t>(p[a]));
    mix(static_cast<uint32_t>(mesh.indices.size()));
    for (const uint32_t index : mesh.indices) mix(index);
  }
  return hash;
}

namespace {

// The instances and their transforms at each shutter time, as the top level is built from.
void instancesAt(const scene::Scene& scene, std::span<const float> times, std::vector<gpu::TraceInstance>& instances,
                 std::vector<gpu::InstanceTransform>& transforms) {
  for (const scene::Instance& instance : scene.instances) {
    const uint32_t material = scene.meshes.at(instance.mesh).material;
    const bool doubleSided = material < scene.materials.size() && scene.materials[material].doubleSided;
    instances.push_back({instance.mesh, instance.objectId, doubleSided ? 0u : HMB_TRACE_INSTANCE_SINGLE_SIDED, 0u});
    for (const float t : times) {
      const glm::mat4 world = scene.worldMatrixAt(instance.node, t);
      transforms.push_back({world, glm::inverse(world)});
    }
  }
}

bool sameInstances(const std::vector<gpu::TraceInstance>& a, const std::vector<gpu::TraceInstance>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
           return x.mesh == y.mesh && x.objectId == y.objectId && x.flags == y.flags;
         });
}

bool sameTransforms(const std::vector<gpu::InstanceTransform>& a, const std::vector<gpu::InstanceTransform>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const auto& x, const auto& y) {
           return x.worldFromObject == y.worldFromObject && x.objectFromWorld == y.objectFromWorld;
         });
}

}  // namespace

gpu::PinholeCamera pinholeCamera(const scene::Scene& scene, float t, uint32_t width, uint32_t height) {
  const FrameCamera camera = frameCamera(scene, t, width, height);
  const glm::mat4 cameraToWorld = glm::inverse(camera.view);
  // projection[0][0] = 1 / (aspect tan(fov / 2)); projection[1][1] = -1 / tan(fov / 2) (y down).
  const float tanX = 1.0f / camera.projection[0][0];
  const float tanY = 1.0f / std::abs(camera.projection[1][1]);
  gpu::PinholeCamera r{};
  r.eye = glm::vec4(camera.eye, 1.0f);
  r.right = glm::vec4(glm::vec3(cameraToWorld[0]) * tanX, 0.0f);
  r.down = glm::vec4(-glm::vec3(cameraToWorld[1]) * tanY, 0.0f);
  r.forward = glm::vec4(-glm::vec3(cameraToWorld[2]), 0.0f);
  return r;
}

TraceScene::TraceScene(const vk::Context& context, const scene::Scene& scene, vk::FrameRecorder& frame)
    : TraceScene(context, scene, frame, passes::BvhBuildShape::forDevice(context)) {}

TraceScene::TraceScene(const vk::Context& context, const scene::Scene& scene, vk::FrameRecorder& frame,
                       const passes::BvhBuildShape& meshShape)
    : TraceScene(context, std::make_shared<MeshTrees>(context, scene, frame, meshShape)) {}

TraceScene::TraceScene(const vk::Context& context, std::shared_ptr<MeshTrees> meshes)
    : context_(context),
      motionBoundsKernel_(context, kernels::kernel("trace/instance_motion_bounds")),
      deformedLeavesKernel_(context, kernels::kernel("bvh/deformed_leaf_triangles")),
      meshes_(std::move(meshes)),
      instanceBvh_(context, "instance BVH", HMB_BVH_MAX_INSTANCE_LEAF, passes::BvhBuildShape::forTopLevel(context)),
      linearInstanceBvh_(context, "instance BVH (linear)") {
  status_ = vk::uploadedBuffer(context, std::vector<uint32_t>(HMB_TRACE_STATUS_WORDS, 0u), "trace status");
}

TraceScene::MeshTrees::MeshTrees(const vk::Context& context, const scene::Scene& scene, vk::FrameRecorder& frame,
                                 const passes::BvhBuildShape& meshShape)
    : bvh(context, "mesh BVH", HMB_BVH_MAX_LEAF, meshShape) {
  const vk::ComputeKernel triangleBoundsKernel(context, kernels::kernel("bvh/triangle_bounds"));
  std::vector<glm::vec4> positions;
  std::vector<glm::uvec4> triangles;
  std::vector<glm::uvec2> roots;
  for (uint32_t m = 0; m < scene.meshes.size(); ++m) {
    const scene::Mesh& mesh = scene.meshes[m];
    const auto base = static_cast<uint32_t>(positions.size());
    for (const glm::vec3& p : mesh.positions) positions.emplace_back(p, 1.0f);
    firstTriangle.push_back(static_cast<uint32_t>(triangles.size()));
    roots.emplace_back(static_cast<uint32_t>(triangles.size()), mesh.triangleCount());
    for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
      triangles.emplace_back(base + mesh.indices[i], base + mesh.indices[i + 1], base + mesh.indices[i + 2], m);
  }
  if (triangles.size() >= HMB_BVH_PACKED_INDEX_LIMIT / 2)
    throw Error("the scene has more triangles than a BVH can index");
  meshCount = static_cast<uint32_t>(scene.meshes.size());
  fingerprint = meshFingerprint(scene);
  triangleCount = static_cast<uint32_t>(triangles.size());
  // The build's input alone: traversal reads leafTriangles (below).
  const vk::Buffer positionBuffer = vk::uploadedBuffer(context, positions, "trace positions");
  const vk::Buffer triangleBuffer = vk::uploadedBuffer(context, triangles, "trace triangles");
  // The boxes serve the build alone: freed before the trees are compacted, to lower the peak.
  vk::Buffer triangleBoxes(context, std::max<size_t>(triangles.size(), 1) * sizeof(gpu::BvhBox), vk::MemoryUse::Device,
                           "triangle boxes");
  if (roots.empty()) roots.emplace_back(0u, 0u);  // a scene without meshes: one empty tree
  const uint32_t count = triangleCount;
  bvh.build(frame, triangleBoxes, count, roots, [&](vk::FrameRecorder& f) {
    f.dispatch(kTriangleBounds, triangleBoundsKernel, {{HMB_TRIANGLE_BOUNDS_BINDING_POSITIONS, &positionBuffer},
                {HMB_TRIANGLE_BOUNDS_BINDING_TRIANGLES, &triangleBuffer},
                {HMB_TRIANGLE_BOUNDS_BINDING_BOXES, &triangleBoxes}},
               count,
               vk::foldedGroups(vk::groupsFor(count, HMB_BVH_BUILD_GROUP)));
  });
  triangleBoxes = {};
  bvh.compact(frame);  // built once, kept for every frame: about half the worst case it was built in
  // Each triangle's vertices in the leaves' order, which traversal reads without the leaves'
  // indirection or the vertex indices (the primitive order names each triangle, for the closest
  // hit only; the indices ride in w, for shading).
  std::vector<glm::vec4> leafTriangles(3 * std::max(count, 1u), glm::vec4(0.0f));
  if (count > 0) {
    const std::vector<uint32_t> order = bvh.primitives().download<uint32_t>();
    for (uint32_t entry = 0; entry < count; ++entry) {
      const glm::uvec4& triangle = triangles.at(order.at(entry));
      for (uint32_t corner = 0; corner < 3; ++corner)
        leafTriangles[3 * entry + corner] =
            glm::vec4(glm::vec3(positions.at(triangle[corner])), std::bit_cast<float>(triangle[corner]));
    }
  }
  this->leafTriangles = vk::uploadedBuffer(context, leafTriangles, "trace triangles (leaf order)");
}

bool TraceScene::MeshTrees::serves(const scene::Scene& scene) const { return meshFingerprint(scene) == fingerprint; }

vk::FrameTimings TraceScene::followDeformation(const scene::Scene& scene, float t, GpuScene& gpuScene,
                                              vk::FrameRecorder& frame) {
  vk::FrameTimings timings;
  if (!gpuScene.deforms() || meshes_->triangleCount == 0) return timings;
  const double preparedMs = prepareRefit(scene, frame);
  if (preparedMs > 0.0) timings = {{{kRefit, preparedMs}}, preparedMs};
  frame.begin();
  gpuScene.recordDeformationAt(scene, t, frame);
  recordRefit(gpuScene, frame);
  vk::appendTimings(timings, frame.submitAndWait());
  return timings;
}

double TraceScene::prepareRefit(const scene::Scene& scene, vk::FrameRecorder& setup) {
  if (meshes_->triangleCount == 0) return 0.0;
  if (deformedBoxes_.size() < uint64_t(meshes_->triangleCount) * sizeof(gpu::BvhBox))
    deformedBoxes_ = vk::Buffer(context_, uint64_t(meshes_->triangleCount) * sizeof(gpu::BvhBox), vk::MemoryUse::Device,
                                "deformed triangle boxes");
  // Only the deforming meshes' trees: a static mesh keeps its triangles and its bounds.
  std::vector<uint32_t> trees;
  for (const scene::Instance& instance : scene.instances)
    if (instance.deforms()) trees.push_back(instance.mesh);
  std::sort(trees.begin(), trees.end());
  trees.erase(std::unique(trees.begin(), trees.end()), trees.end());
  deformedMeshes_.clear();
  for (const uint32_t mesh : trees)
    deformedMeshes_.emplace_back(mesh, meshes_->firstTriangle.at(mesh), scene.meshes.at(mesh).triangleCount());
  return meshes_->bvh.prepareRefit(setup, trees);
}

void TraceScene::recordRefit(const GpuScene& gpuScene, vk::FrameRecorder& frame) {
  if (meshes_->triangleCount == 0) return;
  for (const glm::uvec3 mesh : deformedMeshes_) {
    const glm::uvec2 entries(mesh.y, mesh.z);
    frame.dispatch(kDeformedLeaves, deformedLeavesKernel_,
                   {{HMB_DEFORMED_LEAVES_BINDING_VERTICES, &gpuScene.vertices()},
                    {HMB_DEFORMED_LEAVES_BINDING_PRIMITIVES, &meshes_->bvh.primitives()},
                    {HMB_DEFORMED_LEAVES_BINDING_LEAF_TRIANGLES, &meshes_->leafTriangles},
                    {HMB_DEFORMED_LEAVES_BINDING_BOXES, &deformedBoxes_}},
                   entries, vk::foldedGroups(vk::groupsFor(entries.y, HMB_BVH_BUILD_GROUP)));
  }
  meshes_->bvh.recordRefit(frame, deformedBoxes_, kRefit);
  // The instances' boxes moved: the top level must be built again. (The staged transforms stay:
  // a frame records the refit before the top level's build from them.)
  treeRecorded_ = false;
}

bool TraceScene::hasMeshesOf(const scene::Scene& scene) const { return meshes_->serves(scene); }

bool TraceScene::hasShutterTimes(const scene::Scene& scene, std::span<const float> times) const {
  // Staged and not yet recorded: no tree was built for them.
  if (!treeRecorded_ || (builtTransforms_.empty() && builtInstances_.empty())) return false;
  std::vector<gpu::TraceInstance> instances;
  std::vector<gpu::InstanceTransform> transforms;
  instancesAt(scene, times, instances, transforms);
  return timeCount_ == times.size() && sameInstances(instances, builtInstances_) &&
         sameTransforms(transforms, builtTransforms_);
}

void TraceScene::setShutterTimes(const scene::Scene& scene, std::span<const float> times, vk::FrameRecorder& frame) {
  stageShutterTimes(scene, times);
  buildStagedTree(frame, kInstanceTree);
}

double TraceScene::buildStagedTree(vk::FrameRecorder& frame, std::string_view pass) {
  // This path waits anyway: the transforms (a batch of shutter times can be megabytes) go
  // through the buffers' own writes, not the command buffer.
  instances_.upload(std::span<const gpu::TraceInstance>(builtInstances_));
  transforms_.upload(std::span<const gpu::InstanceTransform>(builtTransforms_));
  frame.begin();
  recordInstanceTree(frame, pass);
  const double milliseconds = frame.submitAndWait().frameMilliseconds.value_or(0.0);
  if (!linearTopLevel_) instanceBvh_.readRecordedCounts(milliseconds);
  instanceTreeMilliseconds_ = milliseconds;
  return milliseconds;
}

void TraceScene::stageShutterTimes(const scene::Scene& scene, std::span<const float> times) {
  if (times.empty()) throw Error("a trace needs at least one shutter time");
  std::vector<gpu::TraceInstance> instances;
  std::vector<gpu::InstanceTransform> transforms;
  instancesAt(scene, times, instances, transforms);
  instanceCount_ = static_cast<uint32_t>(instances.size());
  timeCount_ = static_cast<uint32_t>(times.size());
  // The buffers grow with the instances and are kept otherwise: a frame's transforms are
  // written into them when it runs, and the table that binds them by address stays valid.
  const auto fit = [&](vk::Buffer& buffer, size_t bytes, const char* name) {
    if (buffer.size() < bytes) buffer = vk::Buffer(context_, bytes, vk::MemoryUse::Device, name);
  };
  const size_t slots = std::max<size_t>(instances.size(), 1);
  fit(instances_, slots * sizeof(gpu::TraceInstance), "trace instances");
  fit(transforms_, std::max<size_t>(transforms.size(), 1) * sizeof(gpu::InstanceTransform), "instance transforms");
  fit(instanceBoxes_, slots * sizeof(gpu::BvhBox), "instance boxes");
  // Where enough instances stand still and others move, the still ones' tree is kept from the
  // frame that built it, so long as they are the same instances with the same transforms.
  StillPart still = whyNotSplit(scene, splitFrom_).empty() ? stillPartOf(scene) : StillPart{};
  keepsStillTree_ = !still.order.empty() && servesStill(still);
  if (!keepsStillTree_) stillTreeRecorded_ = false;  // until this frame's split build is recorded
  still_ = std::move(still);
  builtInstances_ = std::move(instances);
  builtTransforms_ = std::move(transforms);
  treeRecorded_ = false;
}

// Still: no animation above the instance's node and no deformation, so its box is the same in
// every frame.
std::pair<std::vector<uint32_t>, uint32_t> TraceScene::stillFirstOrder(const scene::Scene& scene) {
  std::vector<uint32_t> order, moving;
  for (uint32_t i = 0; i < scene.instances.size(); ++i) {
    const scene::Instance& instance = scene.instances[i];
    (instance.deforms() || scene.isAnimated(instance.node) ? moving : order).push_back(i);
  }
  const auto still = static_cast<uint32_t>(order.size());
  order.insert(order.end(), moving.begin(), moving.end());
  return {std::move(order), still};
}

std::string TraceScene::whyNotSplit(const scene::Scene& scene, uint32_t stillInstances) {
  if (stillInstances == 0) return "one tree over all instances: this renderer does not split its top level";
  const uint32_t still = stillFirstOrder(scene).second;
  const auto moving = static_cast<uint32_t>(scene.instances.size()) - still;
  if (moving == 0) return "no instance moves";
  if (still < stillInstances)
    return std::to_string(still) + " still instances, fewer than the " + std::to_string(stillInstances) +
           " for which keeping their tree pays on this device: one tree over all";
  if (moving > HMB_BVH_MAX_INSERTED)
    return std::to_string(moving) + " moving instances, more than are inserted into a kept tree (" +
           std::to_string(HMB_BVH_MAX_INSERTED) + "): one tree over all";
  if (passes::BvhBuildPass::firstSubmissionLevels(still) + moving > HMB_BVH_MAX_DEPTH)
    return std::to_string(moving) + " insertions could take the still instances' tree deeper than traversal's " +
           std::to_string(HMB_BVH_MAX_DEPTH) + " levels: one tree over all";
  return "";
}

TraceScene::StillPart TraceScene::stillPartOf(const scene::Scene& scene) {
  StillPart part;
  std::tie(part.order, part.count) = stillFirstOrder(scene);
  std::vector<gpu::TraceInstance> instances;
  std::vector<gpu::InstanceTransform> transforms;
  const float time = 0.0f;  // the same at every time
  instancesAt(scene, std::span(&time, 1), instances, transforms);
  for (uint32_t k = 0; k < part.count; ++k) {
    part.instances.push_back(instances.at(part.order[k]));
    part.transforms.push_back(transforms.at(part.order[k]));
  }
  return part;
}

bool TraceScene::servesStill(const StillPart& part) const {
  return stillTreeRecorded_ && part.order == still_.order && sameInstances(part.instances, still_.instances) &&
         sameTransforms(part.transforms, still_.transforms);
}

bool TraceScene::hasStillInstanceTreeOf(const scene::Scene& scene) const {
  return whyNotSplit(scene, splitFrom_).empty() && servesStill(stillPartOf(scene));
}

double TraceScene::buildStillInstanceTree(vk::FrameRecorder& frame) {
  if (still_.order.empty() || timeCount_ == 0)
    throw Error("the trace scene's still instances' tree was built without a staged split top level");
  const double milliseconds = buildStagedTree(frame, kStillInstanceTree);
  keepsStillTree_ = true;  // the frames of this staging insert the moving ones alone
  return milliseconds;
}

void TraceScene::recordStagedShutterTimes(vk::FrameRecorder& frame, std::string_view pass) {
  if (timeCount_ == 0)
    throw Error("the trace scene's instance tree was recorded without staged shutter times");
  frame.write(pass, instances_, std::span<const gpu::TraceInstance>(builtInstances_));
  frame.write(pass, transforms_, std::span<const gpu::InstanceTransform>(builtTransforms_));
  recordInstanceTree(frame, pass);
}

void TraceScene::recordInstanceTree(vk::FrameRecorder& frame, std::string_view pass) {
  const gpu::TraceParams params{0u, instanceCount_, timeCount_, 0u};
  const auto motionBounds = [&](vk::FrameRecorder& f) {
    f.dispatch(pass, motionBoundsKernel_,
               {{HMB_MOTION_BOUNDS_BINDING_MESH_NODES, &meshes_->bvh.nodes()},
                {HMB_MOTION_BOUNDS_BINDING_INSTANCES, &instances_},
                {HMB_MOTION_BOUNDS_BINDING_TRANSFORMS, &transforms_},
                {HMB_MOTION_BOUNDS_BINDING_BOXES, &instanceBoxes_},
                {HMB_MOTION_BOUNDS_BINDING_MESH_FRAMES, &meshes_->bvh.frames()}},
               params, vk::foldedGroups(vk::groupsFor(instanceCount_, HMB_TRACE_GROUP)));
  };
  // The still instances' tree kept, the moving ones inserted into it again
  // (bench/results/top-level-insertion/).
  linearTopLevel_ = false;
  if (keepsStillTree_) {
    instanceBvh_.recordInsertionsAgain(frame, pass, instanceBoxes_, motionBounds);
  } else if (!still_.order.empty()) {
    instanceBvh_.recordKeptWithInsertions(frame, pass, instanceBoxes_, still_.order, still_.count, motionBounds);
  } else if (context_.profile().linearTopLevel && instanceCount_ <= HMB_LINEAR_BVH_MAX_PRIMITIVES) {
    linearInstanceBvh_.record(frame, pass, instanceBoxes_, instanceCount_, motionBounds);
    linearTopLevel_ = true;
  } else {
    const glm::uvec2 root(0u, instanceCount_);
    instanceBvh_.record(frame, pass, instanceBoxes_, instanceCount_, std::span(&root, 1), motionBounds);
  }
  stillTreeRecorded_ = !still_.order.empty();
  treeRecorded_ = true;  // only once the whole build is recorded
}

void TraceScene::bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const {
  static_assert(sizeof(gpu::TraceSceneTable) == HMB_TRACE_SCENE_BUFFERS * sizeof(uint64_t));
  // The order of kernels/trace/trace_scene_bindings.glsl and of gpu::TraceSceneTable.
  const bool linear = linearTopLevel_;
  const vk::Buffer* members[] = {linear ? &linearInstanceBvh_.nodes() : &instanceBvh_.nodes(),
                                 linear ? &linearInstanceBvh_.primitives() : &instanceBvh_.primitives(),
                                 &instances_,
                                 &transforms_,
                                 &meshes_->bvh.nodes(),
                                 &meshes_->bvh.primitives(),
                                 &meshes_->leafTriangles,
                                 linear ? &linearInstanceBvh_.frames() : &instanceBvh_.frames(),
                                 &meshes_->bvh.frames(),
                                 &status_};
  group_.bind(bindings, firstBinding, byAddress, members);
}

void TraceScene::resetStatus() {
  status_.upload(std::span<const uint32_t>(std::vector<uint32_t>(HMB_TRACE_STATUS_WORDS, 0u)));
}

void TraceScene::recordResetStatus(vk::FrameRecorder& frame, std::string_view pass) const {
  frame.fill(pass, status_, 0u);
}

uint32_t TraceScene::cutTraces() const {
  return status_.download<uint32_t>().at(HMB_TRACE_STATUS_CUT_TRACES);
}

void planDeformedTrees(FramePlan& plan, const scene::Scene& scene) {
  for (const char* pass : {TraceScene::kDeformedLeaves, TraceScene::kRefit})
    if (scene.hasDeformation())
      plan.run(pass);
    else
      plan.skip(pass, kNoDeformationReason);
}

bool planKeptMeshTrees(FramePlan& plan, std::string_view buildPass, const TraceScene* kept, const scene::Scene& scene) {
  const bool serves = kept && kept->hasMeshesOf(scene);
  if (serves)
    plan.skip(std::string(buildPass),
              "the mesh trees of an earlier frame serve this one: same meshes (positions and triangles)");
  else
    plan.run(std::string(buildPass));
  return serves;
}

std::optional<double> prepareKeptMeshTrees(std::unique_ptr<TraceScene>& kept, std::string_view buildPass,
                                           const FramePlan& plan, const vk::Context& context, const scene::Scene& scene,
                                           vk::FrameRecorder& frame) {
  if (!plan.runs(buildPass)) {
    if (!kept) throw Error(std::string(buildPass) + ": the plan keeps mesh trees never built");
    return std::nullopt;
  }
  kept.reset();
  kept = std::make_unique<TraceScene>(context, scene, frame);
  return kept->meshBvh().stats().deviceMilliseconds;
}

bvh::Bvh TraceScene::downloadInstanceTree() const {
  return linearTopLevel_ ? linearInstanceBvh_.download() : instanceBvh_.download(0);
}

std::vector<gpu::BvhNode> TraceScene::downloadInstanceNodes() const {
  return linearTopLevel_ ? linearInstanceBvh_.downloadNodes() : instanceBvh_.downloadNodes();
}

}  // namespace hmb
