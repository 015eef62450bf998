#include "runtime/methods/raster_frame.h"

#include <utility>

#include <glm/packing.hpp>

#include "hmblur/buffer.h"
#include "hmblur/frame_plan.h"
#include "hmblur/post_process_settings.h"
#include "hmblur/renderer.h"
#include "runtime/passes/encode_display_pass.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/rasterize_pass.h"

namespace hmb {

Beauty linearBeauty(const vk::Buffer& linear) { return {&linear, passes::DisplaySource::LinearRgba}; }

Beauty gbufferBeauty(const passes::GBufferStage& gbuffer) {
  return {&gbuffer.layer().samples(), passes::DisplaySource::LayerSamples};
}

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

GpuScene prepareRasterFrame(FrameResources& resources, const FrameRequest& request, RenderResult& result,
                            const passes::PostProcessSettings* blur, bool still) {
  GpuScene gpuScene(resources.context, request.scene);
  gpuScene.setFrame(request.scene, request.frameTime, request.width, request.height);
  if (!request.settings.skipUnneededPasses) {
    gpuScene.keepTexturePath();
    gpuScene.keepTopLevelWalk();
  }
  const bool curved = blur && blur->motionPath == passes::MotionPath::Curved;
  std::optional<passes::GBufferStage::ShutterPaths> paths;
  if (curved && !still)
    paths = passes::GBufferStage::ShutterPaths{
        blur->exposure, blur->fps,
        shutterClips(request.scene, request.frameTime, blur->exposure, request.width, request.height)};
  resources.gbuffer.prepare(gpuScene, request.width, request.height, paths,
                            curved ? passes::kStillPathsReason : passes::kStraightPathsReason);
  resources.gbuffer.plan(result.plan, gpuScene);
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
                                   const Beauty& beauty,
                                   const std::function<void(vk::FrameRecorder&)>& recordMethodPasses) {
  passes::GBufferStage& gbuffer = resources.gbuffer;
  return passes::submitUntilRasterFits(resources.recorder, gbuffer.rasterizer(), [&](vk::FrameRecorder& frame) {
    gbuffer.record(frame, scene);
    recordMethodPasses(frame);
    resources.encodeDisplay.record(frame, *beauty.buffer, request.display, request.width, request.height, beauty.source);
  });
}

void collectRasterFrame(FrameResources& resources, const FrameRequest& request, const Beauty& beauty,
                        RenderResult& result) {
  const passes::GBufferStage& gbuffer = resources.gbuffer;
  const uint64_t pixels = uint64_t(request.width) * request.height;
  result.memory.gbufferBytesPerPixel = gbuffer.bytesPerPixel(request.width, request.height);
  result.visibilityScheme = passes::visibilitySchemeName(gbuffer.rasterizer().scheme());
  result.raster = gbuffer.rasterizer().stats();

  passes::LayerContents layer = passes::downloadLayer(gbuffer.layer(), pixels);
  // The beauty: the method's own linear image, or the G-buffer's colour where nothing was blurred.
  const bool fromLayer = beauty.source == passes::DisplaySource::LayerSamples;
  std::vector<glm::vec4> color = fromLayer ? std::vector<glm::vec4>() : beauty.buffer->download<glm::vec4>();
  std::vector<glm::vec4> depth, normal, velocity;
  depth.reserve(pixels);
  normal.reserve(pixels);
  velocity.reserve(pixels);
  for (uint64_t i = 0; i < pixels; ++i) {
    if (fromLayer) color.emplace_back(layer.color[i], 1.0f);
    depth.emplace_back(layer.depth[i], 0.0f, 0.0f, 0.0f);
    normal.emplace_back(layer.normal[i], 0.0f);
    velocity.emplace_back(layer.velocity[i], 0.0f, 0.0f);
  }
  io::ImageLayer objectId{"objectId", {"id"}, true, {}, std::move(layer.objectId)};
  result.image = {request.width,
                  request.height,
                  {vec4Layer("", {"R", "G", "B", "A"}, color), vec4Layer("depth", {"Z"}, depth),
                   vec4Layer("normal", {"X", "Y", "Z"}, normal), vec4Layer("velocity", {"X", "Y"}, velocity),
                   std::move(objectId)}};
  // Along curved paths: each pixel's offsets from its point at mid-shutter (MX, MY) and shutter
  // open (OX, OY), pixels, y down; NaN where it has no path (kernels/gbuffer/gbuffer_layout.h).
  if (const vk::Buffer* paths = gbuffer.shutterPaths()) {
    const std::vector<glm::uvec2> records = paths->download<glm::uvec2>();
    std::vector<glm::vec4> offsets;
    offsets.reserve(pixels);
    for (uint64_t i = 0; i < pixels; ++i)
      offsets.emplace_back(glm::unpackHalf2x16(records[i].x), glm::unpackHalf2x16(records[i].y));
    result.image.layers.push_back(vec4Layer("shutterPath", {"MX", "MY", "OX", "OY"}, offsets));
  }
}

}  // namespace hmb
