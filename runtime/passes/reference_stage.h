// The reference renderer (Cook et al. 1984): every pixel sampled at N stratified shutter
// times, each ray traced through the scene at its own time (kernels/reference/). Times are
// taken in batches: a batch's instance transforms and top-level tree are set up once, then one
// dispatch per time sample adds every pixel's shaded sample into its sums, in the fixed order of
// reference_sum_tree.h. The strata are visited in a spread-out order, so the sum after any
// number of samples covers the whole shutter; a checkpoint file (reference_partial.h) lets a
// long render stop after any batch and resume where it stopped; and a render split into shards
// merges (reference_merge.h) to the bits of the whole.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>

#include "hmblur/buffer.h"
#include "hmblur/reference_settings.h"
#include "hmblur/scene.h"
#include "runtime/passes/reference_partial.h"
#include "runtime/passes/reference_sum_tree.h"
#include "runtime/passes/shading_kernel.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/frame_recorder.h"

namespace hmb {
class FramePlan;
class GpuScene;
class TraceScene;
}

namespace hmb::passes {

// Shutter time of each stratum, in the order they are rendered: stratum s covers
// [open + s E / N, open + (s + 1) E / N) and is sampled at a jitter drawn from the seed.
std::vector<float> referenceShutterTimes(float frameTime, float exposure, uint32_t samples, uint32_t seed);

// The kernels that add up and average the reference's sums.
struct ReferenceSumKernels {
  explicit ReferenceSumKernels(const vk::Context& context);
  vk::ComputeKernel fold;     // fold_sums
  vk::ComputeKernel average;  // average_samples
};

// The sum stack's slots (reference_sum_tree.h) on the device: a vec4 a pixel each, kMinSlots
// to kMaxSlots of them as the image's size allows within kDeviceBytes and, where it holds
// kMinSlots, within one storage buffer (a render keeps its deepest nodes in host memory past
// them). One storage buffer holds every slot of a band of rows: one band where a buffer holds
// them all, more for a large image on a device with small storage buffers (lavapipe's are
// 128 MiB). Its additions are fold_sums dispatches
// (ReferenceStage::kFold), their times added to `timings`; uploads and downloads go through the
// buffers' staging.
class DeviceSumSlots final : public SumSlots {
 public:
  static constexpr uint32_t kMinSlots = 3;
  static constexpr uint32_t kMaxSlots = 10;
  static constexpr uint64_t kDeviceBytes = uint64_t(512) << 20;

  struct Band {
    uint32_t firstRow;
    uint32_t rows;
    vk::Buffer sums;  // count() slots of rows x width vec4
  };

  // Throws hmb::Error in one line when one storage buffer cannot hold the slots of one row.
  DeviceSumSlots(const vk::Context& context, vk::FrameRecorder& frame, const ReferenceSumKernels& kernels,
                 uint32_t width, uint32_t height, vk::FrameTimings& timings);

  const std::vector<Band>& bands() const { return bands_; }
  uint32_t count() const override { return count_; }
  void upload(uint32_t slot, std::span<const glm::vec4> sums) override;
  std::vector<glm::vec4> download(uint32_t slot) override;
  void clear(uint32_t slot) override;
  void add(std::span<const glm::uvec2> pairs) override;
  // Writes the mean of the sums in `slot` into `color` (ReferenceStage::kAverage).
  void average(uint32_t slot, const vk::Buffer& color);

 private:
  uint64_t bandPixels(const Band& band) const { return uint64_t(band.rows) * width_; }
  VkDeviceSize offsetOf(const Band& band, uint32_t slot) const { return slot * bandPixels(band) * sizeof(glm::vec4); }

  const vk::Context& context_;
  vk::FrameRecorder& frame_;
  const ReferenceSumKernels& kernels_;
  uint32_t width_;
  uint32_t count_;
  std::vector<Band> bands_;
  vk::FrameTimings& timings_;
};

class ReferenceStage {
 public:
  static constexpr const char* kBvhMeshes = "reference-bvh-meshes";
  static constexpr const char* kBvhInstances = "reference-bvh-instances";
  static constexpr const char* kMovingPixels = "reference-find-moving-pixels";
  static constexpr const char* kAccumulate = "reference-accumulate-sample";
  static constexpr const char* kFold = "reference-fold-sums";
  static constexpr const char* kAverage = "reference-average";

  // hits: how samples shade what they hit (null: the library's shading).
  explicit ReferenceStage(const vk::Context& context, const HitShading* hits = nullptr);
  ~ReferenceStage();

  // The mesh trees of the last render are kept, and serve the next one when its meshes are
  // the same (an animation's frames): the plan then skips kBvhMeshes.
  void plan(FramePlan& plan, const scene::Scene& scene, float frameTime, uint32_t width, uint32_t height,
            const ReferenceSettings& settings) const;
  // Drops the kept trees: the next plan builds them.
  void forgetTraceScene();
  // After render(): its traces the device's loop limit cut short (TraceScene::cutTraces).
  uint32_t cutTraces() const;

  // Renders the mean of the samples (the shard's, for a shard) into `color` (vec4 per pixel,
  // row 0 at the top) and
  // returns the device time of every submission it made, merged. `gpuScene` must have its
  // frame set (materials, the light); its deforming meshes are deformed to each shutter time
  // in turn (one time per batch). `plan` is this frame's, from plan(). `progress` is called
  // after every submission.
  vk::FrameTimings render(vk::FrameRecorder& frame, const scene::Scene& scene, GpuScene& gpuScene,
                          float frameTime, uint32_t width, uint32_t height, const ReferenceSettings& settings,
                          const FramePlan& plan, const vk::Buffer& color,
                          const std::function<void(const ReferenceProgress&)>& progress);

  const ReferenceProgress& lastProgress() const { return progress_; }

 private:
  // The list of moving pixels when the camera stands still (sets progress_.movingPixels), else
  // a placeholder buffer.
  vk::Buffer findMovingPixels(vk::FrameRecorder& frame, const scene::Scene& scene, std::span<const float> times,
                              uint32_t width, uint32_t height, const ReferenceSettings& settings, float tMin,
                              float tMax, vk::FrameTimings& timings);

  const vk::Context& context_;
  vk::ComputeKernel findMovingPixels_;
  ShadingKernel accumulate_;
  ReferenceSumKernels sumKernels_;
  const HitShading* hits_;
  ReferenceProgress progress_;
  std::unique_ptr<TraceScene> traceScene_;
};

}  // namespace hmb::passes
