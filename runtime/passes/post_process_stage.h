// The post-process motion blur stage: tile-max -> neighbour-max -> gather (McGuire et al. 2012
// with the paper's weights, centred or adapted range) or gather-jimenez (Jimenez 2014), from a
// G-buffer layer into an output colour buffer. Owns the two tile buffers.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "runtime/passes/gather_pass.h"
#include "runtime/passes/jimenez_gather_pass.h"
#include "runtime/passes/neighbor_max_pass.h"
#include "runtime/passes/post_process_settings.h"
#include "runtime/passes/tile_max_pass.h"
#include "runtime/vulkan/buffer.h"

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

  void plan(FramePlan& plan) const;
  // The tile passes alone (for stages that run their own gathers).
  void planTiles(FramePlan& plan) const;

  // Sizes the tile buffers for this resolution (reuses them when it is unchanged).
  void prepare(uint32_t width, uint32_t height);
  // inputs: the layer to blur, at the prepared size. output: width * height vec4.
  // mask: width * height uint (0/1) for the McGuire gather's mask options, or nullptr.
  void record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const vk::Buffer& output,
              const vk::Buffer* mask = nullptr) const;
  // The same in parts, for layers that share one set of tiles (the hybrid method): the tile
  // passes over `inputs`' velocities, then McGuire gathers of any layer with any options.
  void recordTiles(vk::FrameRecorder& frame, const MotionBlurInputs& inputs) const;
  void recordGather(vk::FrameRecorder& frame, const MotionBlurInputs& inputs, const GatherOptions& options,
                    const vk::Buffer& output, std::string_view passName) const;

  const PostProcessSettings& settings() const { return settings_; }
  TileGrid tileGrid() const { return grid_; }
  const vk::Buffer& tileMax() const { return tileMax_; }
  const vk::Buffer& neighborMax() const { return neighborMax_; }

 private:
  // Throws hmb::Error when the inputs are not the size prepare() was given.
  void requirePreparedSize(const MotionBlurInputs& inputs) const;

  const vk::Context& context_;
  PostProcessSettings settings_;
  TileMaxPass tileMaxPass_;
  NeighborMaxPass neighborMaxPass_;
  std::optional<GatherPass> gather_;
  std::optional<JimenezGatherPass> jimenezGather_;
  uint32_t width_ = 0, height_ = 0;
  TileGrid grid_;
  vk::Buffer tileMax_, neighborMax_;
};

}  // namespace hmb::passes
