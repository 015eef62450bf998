// The hybrid method (paper, section 3): on top of the G-buffer,
//   tile-max, neighbour-max of the raster's velocities -> ray mask (RayMaskStage, over the
//   moving tiles) -> the post-process gather of the raster layer (GatherPass; outside the mask on
//   a GPU)
//   -> ray reveal (RevealPass) at mask pixels -> gather of the background layer (the revealed
//   surfaces over the raster) at mask pixels only (BackgroundGatherPass, indirect) -> the
//   background composited in at mask pixels (CompositePass, indirect;
//   kernels/reveal/composite.comp says how). With shutter rays (settings' shutterRays, the
//   default) the mask's own passes, the reveal and the composite are left out: post-process's
//   gather covers the image, and at the moving pixels whose path crosses an edge (object or
//   colour) rays at stratified shutter times replace its colour (ShutterRaysPass), the mask's
//   pixels among them.
// Owns the trace scene (mesh trees built once per scene, the instance tree per frame), the
// mask and the revealed surfaces.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "hmblur/buffer.h"
#include "hmblur/hybrid_settings.h"
#include "hmblur/scene.h"
#include "kernels/trace/trace_layout.h"
#include "runtime/passes/background_gather_pass.h"
#include "runtime/passes/composite_pass.h"
#include "runtime/passes/gather_pass.h"
#include "runtime/passes/image_size.h"
#include "runtime/passes/pass_list.h"
#include "runtime/passes/ray_mask_stage.h"
#include "runtime/passes/reveal_pass.h"
#include "runtime/passes/shutter_rays_pass.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {
class FramePlan;
class GpuScene;
class TraceScene;
struct SharedMeshTrees;
}

namespace hmb::passes {

class PostProcessStage;

// Why a hybrid-rays frame skips the ray mask's own passes, the reveal and the composite.
inline constexpr const char* kRevealLeftToShutterRaysReason =
    "hybrid-rays traces shutter rays at every pixel whose path crosses an edge in place of the ray mask's reveal "
    "(--method hybrid reveals the mask, as the paper does; under --ray-budget the pixels left untraced keep it)";
// Why a hybrid-rays frame without a ray budget skips the budget's pass.
inline constexpr const char* kNoRayBudgetReason = "no ray budget: every listed pixel traces its rays";
// Why a stage that shares its mesh trees skips their build.
inline constexpr const char* kSharedMeshTreesReason =
    "the meshes' trees another frame in flight built serve this one: frames in flight share them";
// Why the paper's hybrid skips the shutter rays' passes.
inline constexpr const char* kShutterRaysOffReason = "the paper's method traces no shutter rays (hybrid-rays does)";

class HybridStage {
 public:
  static constexpr const char* kBvhMeshes = "hybrid-bvh-meshes";        // scene setup: not in the frame time
  // scene setup, in the plan only where the top level is split (TraceScene::splitTopLevel):
  // the still instances' tree
  static constexpr const char* kBvhStillInstances = "hybrid-bvh-still-instances";
  static constexpr const char* kBvhInstances = "hybrid-bvh-instances";  // per frame
  static constexpr const char* kGatherBackground = BackgroundGatherPass::kName;
  static constexpr const char* kComposite = CompositePass::kName;
  static constexpr const char* kShutterRaysList = ShutterRaysPass::kList;
  static constexpr const char* kShutterRaysBudget = ShutterRaysPass::kBudget;
  static constexpr const char* kShutterRaysTrace = ShutterRaysPass::kTrace;

  // postProcess: the stage whose tiles and gather both layers use (configured for the
  // McGuire filter and the adapted range by the caller).
  // hits: how the reveal shades what it finds (null: the library's shading).
  HybridStage(const vk::Context& context, PostProcessStage& postProcess, const HitShading* hits = nullptr);
  ~HybridStage();

  // The hybrid's passes for a frame of `scene` at `frameTime` with `settings`: the trace
  // scene's trees are skipped when the last frame's serve (same meshes; no instance moved,
  // nothing deforms), as prepare() does. Deforming meshes are refitted every frame.
  void plan(FramePlan& plan, const scene::Scene& scene, float frameTime, const HybridSettings& settings) const;
  // Builds the trace scene of `scene` (its mesh trees: returned as setup time, waited for)
  // where `plan` (this stage's plan() for the same frame) runs it, keeping the last frame's
  // where it skips it; stages the instances at the frame time for record(), which builds their
  // tree in the frame where the plan runs kBvhInstances, and refits the deforming meshes'
  // trees there (the first refit after a build has a setup part, waited for here); sizes the
  // buffers. Nothing else waits: the frame's own work is all record()'s.
  struct PrepareTimings {
    vk::FrameTimings setup;
    vk::FrameShape setupShape;  // what the setup recorded and waited for (vk::FrameShape)
  };
  PrepareTimings prepare(vk::FrameRecorder& frame, const scene::Scene& scene, float frameTime, uint32_t width,
                         uint32_t height, const HybridSettings& settings, const FramePlan& plan);
  // After the G-buffer (`raster`: the renderer's, or an engine's packed) and the frame's
  // deformation (GpuScene::recordFrameDeformation) in the same frame: writes the blurred,
  // composited colour to `output`. The refits, the instance tree and the camera rays are built
  // and written in the frame: nothing here submits or waits.
  // shutterPaths: the raster's paths over the shutter (GBufferStage::shutterPaths), which the
  // curved path (settings' blur.motionPath) needs; null otherwise.
  // Records the passes `plan` (the frame's, planned by plan() and given to prepare()) runs.
  void record(vk::FrameRecorder& frame, const FramePlan& plan, const ImageLayer& raster, const GpuScene& gpuScene,
              const vk::Buffer& output, const vk::Buffer* shutterPaths = nullptr);

  // The next frame builds its trees anew, whatever the last frame built.
  void forgetTraceScene();
  // Frames in flight: every stage given the same holder traces the mesh trees the last of them
  // built (while the meshes are the same), each over a top level of its own. A scene whose
  // meshes deform is not shared: its refits change the trees of the frame that runs them.
  void shareMeshTrees(std::shared_ptr<SharedMeshTrees> shared);
  // After a frame: its traces the device's loop limit cut short (TraceScene::cutTraces).
  uint32_t cutTraces() const;

  const RayMaskStage& rayMask() const { return rayMask_; }
  const ShutterRaysPass& shutterRays() const { return shutterRays_; }
  // Whether the frame prepare()d traces shutter rays (the plan runs them).
  bool tracesShutterRays() const { return shutterStrata_ != 0; }
  // After prepare(): the meshes' trees (nodes, triangle indices) in bytes per mesh
  // triangle (each mesh's tree is built once, however many instances it has), as allocated
  // and as built; none without triangles.
  struct TreeBytes {
    double allocatedPerTriangle = 0, usedPerTriangle = 0;
  };
  std::optional<TreeBytes> meshTreeBytes() const;
  // What the reveal found, written at mask pixels only (the rest is stale).
  const ImageLayer& revealed() const { return revealed_; }

 private:
  // What the hybrid's passes read: the plan's scene, time and settings, and the recording's
  // layers, buffers and parameters.
  struct Frame {
    const scene::Scene* scene = nullptr;
    float frameTime = 0.0f;
    const HybridSettings* settings = nullptr;
    const ImageLayer* layer = nullptr;
    const GpuScene* gpuScene = nullptr;
    const vk::Buffer* output = nullptr;
    MotionBlurInputs raster;
    gpu::GatherParams blur{};
    RayMaskParameters mask;
  };

  // plan()'s trees: the meshes', the refits, the instances' and the still instances'.
  void planTrees(FramePlan& plan, const scene::Scene& scene, float frameTime, const HybridSettings& settings) const;
  // The cameras' upload and the traces' status reset, timed with the first pass that traces.
  void recordTraceStart(vk::FrameRecorder& frame, const char* pass) const;

  const vk::Context& context_;
  PassList<Frame> passes_;  // in frame order
  PostProcessStage& postProcess_;
  RayMaskStage rayMask_;
  RevealPass reveal_;
  GatherPass gather_;  // post-process's (outside the mask on a GPU)
  BackgroundGatherPass backgroundGather_;
  CompositePass composite_;
  ShutterRaysPass shutterRays_;
  HybridSettings settings_;
  std::unique_ptr<TraceScene> traceScene_;
  std::shared_ptr<SharedMeshTrees> sharedTrees_;  // shareMeshTrees()'s, or none
  // Whether this frame traces the shared trees (they hold the scene's meshes, which do not deform).
  bool takesSharedTrees(const scene::Scene& scene) const;
  ImageSize size_;
  // The shutter strata the frame traces rays at (0 when it traces none), and the camera at each
  // of the trace scene's times (the frame's first, then the strata's), written into cameraRays_
  // by record().
  uint32_t shutterStrata_ = 0;
  std::vector<gpu::PinholeCamera> cameras_;
  bool reveals_ = true;  // the frame reveals the ray mask (else its shutter rays stand in)
  bool candidatesInTileMaxLoop_ = true;  // RayMaskParameters': a GPU, or the camera moves this frame
  vk::Buffer cameraRays_;
  ImageLayer revealed_;
  vk::Buffer backgroundBlurred_;  // the weights composite's blurred background (none beside the coverage composite)
};

}  // namespace hmb::passes
