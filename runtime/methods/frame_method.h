// The interface every method implements, and what the renderer hands it: the devices' shared
// stages (the G-buffer every raster method starts from, the post-process blur the hybrid
// extends, the display encoding) and the frame asked for. A method plans its frame, prepares
// and records its passes, submits them, and fills the result; what it builds for one frame
// and keeps for the next (mesh trees) it owns.
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/vulkan/frame_recorder.h"

namespace hmb {
struct RenderResult;
struct RenderSettings;
namespace scene {
struct Scene;
}
namespace vk {
class Buffer;
class Context;
}
namespace passes {
class EncodeDisplayPass;
class GBufferStage;
class PostProcessStage;
class HitShading;
}

struct FrameResources {
  const vk::Context& context;
  vk::FrameRecorder& recorder;
  passes::EncodeDisplayPass& encodeDisplay;
  passes::GBufferStage& gbuffer;
  passes::PostProcessStage& postProcess;
  const passes::HitShading& hitShading;  // how the reveal and the reference shade ray hits
};

struct FrameRequest {
  const scene::Scene& scene;
  const RenderSettings& settings;  // validated
  float frameTime = 0.0f;
  uint32_t width = 0, height = 0;
  const vk::Buffer& display;  // RGBA8 per pixel: the method encodes its image into it
};

class FrameMethod {
 public:
  virtual ~FrameMethod() = default;
  // Plans the frame into result.plan, records and submits its passes, and fills result.image
  // and the method's counts; returns the passes' device times.
  virtual vk::FrameTimings render(const FrameRequest& request, RenderResult& result) = 0;
};

// Each method's file: its factory and the check of its settings (runtime/methods/method.cpp
// lists them).
std::unique_ptr<FrameMethod> makeSharpMethod(FrameResources& resources);
std::unique_ptr<FrameMethod> makePostProcessMethod(FrameResources& resources);
void validatePostProcessMethod(const RenderSettings& settings);
std::unique_ptr<FrameMethod> makeHybridMethod(FrameResources& resources);
void validateHybridMethod(const RenderSettings& settings);
std::unique_ptr<FrameMethod> makeReferenceMethod(FrameResources& resources);
void validateReferenceMethod(const RenderSettings& settings);
std::unique_ptr<FrameMethod> makeTestPatternMethod(FrameResources& resources);

}  // namespace hmb
