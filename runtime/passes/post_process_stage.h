// The post-process motion blur stage: tile-max -> neighbour-max -> the chosen filter's gather
// (post_process_filter.h), from a G-buffer layer into an output colour buffer. Owns the two
// tile buffers and the gathers it has used.
#pragma once

#include <cstdint>
#include <map>
#include <memory>

#include "hmblur/buffer.h"
#include "hmblur/post_process_settings.h"
#include "runtime/passes/gather_filter.h"
#include "runtime/passes/image_size.h"
#include "runtime/passes/neighbor_max_pass.h"
#include "runtime/passes/pass_list.h"
#include "runtime/passes/tile_max_pass.h"

namespace hmb {
class FramePlan;
}

namespace hmb::passes {

class PostProcessStage {
 public:
  // Validates the settings (hmb::Error on absurd values) and builds the selected filter's kernels.
  PostProcessStage(const vk::Context& context, const PostProcessSettings& settings);
  // Validates and takes new settings (throws hmb::Error); call prepare() again after it.
  void configure(const PostProcessSettings& settings);

  // Its passes (passes_) into the frame's plan.
  void plan(FramePlan& plan) const;
  // The tile passes alone (for stages that run their own gathers).
  void planTiles(FramePlan& plan) const;

  // Sizes the tile buffers for this resolution (reuses them when it is unchanged).
  void prepare(uint32_t width, uint32_t height);
  // inputs: the layer to blur, at the prepared size. output: width * height vec4. Records the
  // passes `plan` runs; without a plan, every pass of plan().
  void record(vk::FrameRecorder& frame, const FramePlan& plan, const MotionBlurInputs& inputs,
              const vk::Buffer& output) const;
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& output) const;
  // The tile passes alone over `inputs`' velocities, for stages that run their own gathers
  // on neighborMax() (the hybrid method).
  void recordTiles(vk::FrameRecorder& frame, const MotionBlurInputs& inputs) const;
  // Neighbour-max alone, over a tile-max another stage wrote into tileMax() (the hybrid's ray
  // mask, whose tile-max also lists its edge candidates).
  void recordNeighborMax(vk::FrameRecorder& frame) const;

  const PostProcessSettings& settings() const { return settings_; }
  TileGrid tileGrid() const { return grid_; }
  const vk::Buffer& tileMax() const { return tileMax_; }
  const vk::Buffer& neighborMax() const { return neighborMax_; }

 private:
  // Throws hmb::Error when the inputs are not the size prepare() was given.
  void requirePreparedSize(const MotionBlurInputs& inputs) const;

  // What the stage's passes read this frame.
  struct Frame {
    const MotionBlurInputs* inputs = nullptr;
    const vk::Buffer* output = nullptr;
  };

  const vk::Context& context_;
  PassList<Frame> tilePasses_;  // tile-max, neighbour-max
  PassList<Frame> passes_;      // the tile passes, then the filter's
  PostProcessSettings settings_;
  TileMaxPass tileMaxPass_;
  NeighborMaxPass neighborMaxPass_;
  std::map<PostProcessFilter, std::unique_ptr<GatherFilter>> filters_;
  ImageSize size_;
  TileGrid grid_;
  vk::Buffer tileMax_, neighborMax_;
};

}  // namespace hmb::passes
