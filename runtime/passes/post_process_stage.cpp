#include "runtime/passes/post_process_stage.h"

#include <string>

#include <glm/glm.hpp>

#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "kernels/mblur/mblur_layout.h"

namespace hmb::passes {

vk::Bindings filterBindings(const MotionBlurInputs& inputs, const vk::Buffer& neighborMax,
                            const vk::Buffer& output) {
  return {{HMB_FILTER_BINDING_SAMPLES, inputs.samples},
          {HMB_FILTER_BINDING_NEIGHBOR_MAX, &neighborMax},
          {HMB_FILTER_BINDING_OUTPUT, &output},
          // Read only along curved paths; any texel buffer stands in otherwise.
          {HMB_FILTER_BINDING_SHUTTER_PATHS, inputs.shutterPaths ? inputs.shutterPaths : inputs.samples}};
}

void GatherFilter::plan(FramePlan& plan) const { plan.run(std::string(passName())); }

PostProcessStage::PostProcessStage(const vk::Context& context, const PostProcessSettings& settings)
    : context_(context), tilePasses_(context), passes_(context), tileMaxPass_(context), neighborMaxPass_(context) {
  configure(settings);
  tilePasses_
      .pass(TileMaxPass::kName,
            [this](vk::FrameRecorder& frame, const Frame& f) {
              requirePreparedSize(*f.inputs);
              tileMaxPass_.record(frame, *f.inputs->velocities, tileMax_, f.inputs->width, f.inputs->height,
                                  settings_.effectiveTileSize(), settings_.velocityScale());
            })
      .pass(NeighborMaxPass::kName, [this](vk::FrameRecorder& frame, const Frame&) { recordNeighborMax(frame); });
  passes_.include(tilePasses_)
      // The chosen filter's gather and the passes it records beside it.
      .group([this](FramePlan& plan, const Frame&) { filters_.at(settings_.filter)->plan(plan); },
             [this](vk::FrameRecorder& frame, const FramePlan& plan, const Frame& f) {
               const GatherFilter& filter = *filters_.at(settings_.filter);
               if (plan.runs(filter.passName())) filter.record(frame, *f.inputs, neighborMax_, *f.output, settings_);
             });
}

void PostProcessStage::configure(const PostProcessSettings& settings) {
  validate(settings);
  settings_ = settings;
  // Pipelines compile once each and cost time on CPU devices: a gather is built when first used.
  std::unique_ptr<GatherFilter>& filter = filters_[settings_.filter];
  if (!filter) filter = describe(settings_.filter).make(context_);
  size_.forget();  // the tile grid follows the tile size: prepare() sizes it again
}

void PostProcessStage::planTiles(FramePlan& plan) const { tilePasses_.plan(plan); }

void PostProcessStage::plan(FramePlan& plan) const { passes_.plan(plan); }

void PostProcessStage::prepare(uint32_t width, uint32_t height) {
  if (width == 0 || height == 0) throw Error("post-process: empty image");
  if (!size_.changesTo(width, height)) return;
  grid_ = tileGridFor(width, height, settings_.effectiveTileSize());
  // tile_max runs one group per tile; 65535 is the smallest group-count limit Vulkan allows.
  if (grid_.x > 65535 || grid_.y > 65535)
    throw Error("post-process: " + std::to_string(width) + "x" + std::to_string(height) + " needs more than 65535 tiles " +
                "in a row at tile size " + std::to_string(settings_.effectiveTileSize()));
  const uint64_t bytes = uint64_t(grid_.count()) * sizeof(glm::vec4);
  tileMax_ = vk::Buffer(context_, bytes, vk::MemoryUse::Device, "tile max");
  neighborMax_ = vk::Buffer(context_, bytes, vk::MemoryUse::Device, "neighbor max");
  size_.madeFor(width, height);
}

void PostProcessStage::requirePreparedSize(const MotionBlurInputs& inputs) const {
  size_.requireMadeFor("post-process", inputs.width, inputs.height);
}

void PostProcessStage::recordTiles(vk::FrameRecorder& frame, const MotionBlurInputs& inputs) const {
  tilePasses_.recordAll(frame, {&inputs, nullptr});
}

void PostProcessStage::recordNeighborMax(vk::FrameRecorder& frame) const {
  if (!tileMax_.handle()) throw Error("post-process: recordNeighborMax() before prepare()");
  neighborMaxPass_.record(frame, tileMax_, neighborMax_, grid_, settings_.neighborhood);
}

void PostProcessStage::record(vk::FrameRecorder& frame, const FramePlan& plan, const MotionBlurInputs& inputs,
                              const vk::Buffer& output) const {
  passes_.record(frame, plan, {&inputs, &output});
}

void PostProcessStage::record(vk::FrameRecorder& frame, const MotionBlurInputs& inputs,
                              const vk::Buffer& output) const {
  passes_.recordAll(frame, {&inputs, &output});
}

}  // namespace hmb::passes
