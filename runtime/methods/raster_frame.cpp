#include "runtime/methods/raster_frame.h"

#include <utility>

#include "runtime/frame_plan.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/renderer.h"
#include "runtime/vulkan/buffer.h"

namespace hmb {

io::ImageLayer vec4Layer(const std::string& name, std::vector<std::string> channels,
                         const std::vector<glm::vec4>& values) {
  io::ImageLayer layer{name, std::move(channels), false, {}, {}};
  const size_t n = layer.channels.size();
  layer.values.reserve(values.size() * n);
  for (const glm::vec4& v : values)
    for (size_t c = 0; c < n; ++c) layer.values.push_back(v[int(c)]);
  return layer;
}

vk::Buffer linearImageBuffer(const FrameResources& resources, const FrameRequest& request, std::string name) {
  return vk::Buffer(resources.context, uint64_t(request.width) * request.height * sizeof(glm::vec4),
                    vk::MemoryUse::Device, std::move(name));
}

io::LayeredImage beautyImage(const FrameRequest& request, const vk::Buffer& linear) {
  return {request.width, request.height, {vec4Layer("", {"R", "G", "B", "A"}, linear.download<glm::vec4>())}};
}

GpuScene prepareRasterFrame(FrameResources& resources, const FrameRequest& request, RenderResult& result) {
  GpuScene gpuScene(resources.context, request.scene);
  gpuScene.setFrame(request.scene, request.frameTime, request.width, request.height);
  if (!request.settings.skipUnneededPasses) gpuScene.keepTexturePath();
  resources.gbuffer.prepare(gpuScene, request.width, request.height);
  resources.gbuffer.plan(result.plan);
  return gpuScene;
}

bool nothingMovesOnScreen(const FrameRequest& request) {
  return request.settings.skipUnneededPasses && !anythingMovesOnScreen(request.scene, request.frameTime);
}

void planBlur(FramePlan& plan, const FramePlan& blurPlan, bool still) {
  for (const PlannedPass& pass : blurPlan.passes()) {
    if (still)
      plan.skip(pass.name, "nothing moves on screen at this frame: every velocity is 0, so the blur "
                           "returns the sharp colour");
    else if (pass.run)
      plan.run(pass.name);
    else
      plan.skip(pass.name, pass.reason);
  }
}

vk::FrameTimings recordRasterFrame(FrameResources& resources, const FrameRequest& request, const GpuScene& scene,
                                   const vk::Buffer& beauty,
                                   const std::function<void(vk::FrameRecorder&)>& recordMethodPasses) {
  passes::GBufferStage& gbuffer = resources.gbuffer;
  return passes::submitUntilRasterFits(resources.recorder, gbuffer.rasterizer(), [&](vk::FrameRecorder& frame) {
    gbuffer.record(frame, scene);
    recordMethodPasses(frame);
    resources.encodeDisplay.record(frame, beauty, request.display, request.width, request.height);
  });
}

void collectRasterFrame(FrameResources& resources, const FrameRequest& request, const vk::Buffer& beauty,
                        RenderResult& result) {
  const passes::GBufferStage& gbuffer = resources.gbuffer;
  const uint64_t pixels = uint64_t(request.width) * request.height;
  result.memory.gbufferBytesPerPixel = gbuffer.bytesPerPixel(request.width, request.height);
  result.visibilityScheme = passes::visibilitySchemeName(gbuffer.rasterizer().scheme());
  result.raster = gbuffer.rasterizer().stats();

  const auto normalDepth = gbuffer.normalDepth().download<glm::vec4>();
  std::vector<glm::vec4> depth(normalDepth.size());
  for (size_t i = 0; i < depth.size(); ++i) depth[i].x = normalDepth[i].w;
  std::vector<glm::vec4> velocity;
  for (const glm::vec2& v : gbuffer.velocity().download<glm::vec2>()) velocity.emplace_back(v, 0.0f, 0.0f);
  io::ImageLayer objectId{"objectId", {"id"}, true, {}, gbuffer.objectId().download<uint32_t>()};
  objectId.ids.resize(pixels);
  result.image = {request.width,
                  request.height,
                  {vec4Layer("", {"R", "G", "B", "A"}, beauty.download<glm::vec4>()),
                   vec4Layer("depth", {"Z"}, depth), vec4Layer("normal", {"X", "Y", "Z"}, normalDepth),
                   vec4Layer("velocity", {"X", "Y"}, velocity), std::move(objectId)}};
}

}  // namespace hmb
