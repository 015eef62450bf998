#include "runtime/engine_motion_blur.h"

#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "kernels/engine/engine_layout.h"
#include "runtime/error.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/compute_kernel.h"
#include "runtime/vulkan/context.h"

namespace hmb {
namespace {

constexpr const char* kPackPass = "pack-engine-gbuffer";

uint32_t conventionCode(EngineDepth::Convention convention) {
  switch (convention) {
    case EngineDepth::Convention::CameraSpace: return HMB_ENGINE_DEPTH_VIEW;
    case EngineDepth::Convention::StandardZ: return HMB_ENGINE_DEPTH_STANDARD_Z;
    case EngineDepth::Convention::ReversedZ: return HMB_ENGINE_DEPTH_REVERSED_Z;
  }
  return HMB_ENGINE_DEPTH_VIEW;
}

void validateDepth(const EngineDepth& depth) {
  if (depth.convention == EngineDepth::Convention::CameraSpace) return;
  if (!(std::isfinite(depth.near) && depth.near > 0.0f))
    throw Error("engine depth: a z/w depth needs the projection's near plane, a finite distance > 0");
  const bool infiniteFar = std::isinf(depth.far) && depth.far > 0.0f;
  if (infiniteFar && depth.convention == EngineDepth::Convention::StandardZ)
    throw Error("engine depth: standard z/w needs a finite far plane (an infinite one is reversed-z)");
  if (!infiniteFar && !(std::isfinite(depth.far) && depth.far > depth.near))
    throw Error("engine depth: the far plane must lie beyond the near plane");
}

}  // namespace

struct EngineMotionBlur::Passes {
  Passes(const vk::Context& context, uint32_t width, uint32_t height, const passes::PostProcessSettings& settings)
      : pack(context, "engine/pack_engine_gbuffer", sizeof(gpu::EngineGBufferParams)),
        blur(context, settings),
        layer(passes::ImageLayer::allocate(context, uint64_t(width) * height, "engine G-buffer")),
        recorder(context) {
    blur.prepare(width, height);
  }
  vk::ComputeKernel pack;
  passes::PostProcessStage blur;
  passes::ImageLayer layer;
  vk::FrameRecorder recorder;
};

EngineMotionBlur::EngineMotionBlur(const vk::Context& context, uint32_t width, uint32_t height,
                                   const passes::PostProcessSettings& settings, EngineDepth depth)
    : context_(context), width_(width), height_(height), depth_(depth) {
  if (width == 0 || height == 0) throw Error("engine motion blur: an empty image");
  validateDepth(depth);
  passes_ = std::make_unique<Passes>(context, width, height, settings);
}

EngineMotionBlur::~EngineMotionBlur() = default;

void EngineMotionBlur::record(VkCommandBuffer commandBuffer, const EngineGBuffer& gbuffer, VkBuffer output) {
  const uint64_t pixels = uint64_t(width_) * height_;
  const vk::Buffer color = vk::Buffer::adopt(context_, gbuffer.color, pixels * sizeof(glm::vec4), "engine colour");
  const vk::Buffer depth = vk::Buffer::adopt(context_, gbuffer.depth, pixels * sizeof(float), "engine depth");
  const vk::Buffer velocity =
      vk::Buffer::adopt(context_, gbuffer.velocity, pixels * sizeof(glm::vec2), "engine velocity");
  const vk::Buffer blurred = vk::Buffer::adopt(context_, output, pixels * sizeof(glm::vec4), "engine output");

  gpu::EngineGBufferParams params{};
  params.width = width_;
  params.height = height_;
  params.depthConvention = conventionCode(depth_.convention);
  params.near = depth_.near;
  params.far = depth_.far;
  vk::FrameRecorder& frame = passes_->recorder;
  const passes::ImageLayer& layer = passes_->layer;
  frame.beginInto(commandBuffer);
  frame.dispatch(kPackPass, passes_->pack,
                 {{HMB_ENGINE_BINDING_COLOR, &color},
                  {HMB_ENGINE_BINDING_DEPTH, &depth},
                  {HMB_ENGINE_BINDING_VELOCITY, &velocity},
                  {HMB_ENGINE_BINDING_SAMPLES, &layer.samples()},
                  {HMB_ENGINE_BINDING_SURFACES, &layer.surfaces()}},
                 params,
                 {vk::groupsFor(width_, HMB_ENGINE_GROUP_X), vk::groupsFor(height_, HMB_ENGINE_GROUP_Y), 1});
  passes_->blur.record(frame, {&layer.samples(), &layer.surfaces(), width_, height_}, blurred);
  frame.endInto();
}

vk::FrameTimings EngineMotionBlur::timings() const { return passes_->recorder.readTimings(); }

}  // namespace hmb
