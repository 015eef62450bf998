// What the raster methods (sharp, post-process, hybrid) share around their own passes: the
// scene on the device at the frame time, the G-buffer planned and prepared, the blur's plan
// (left out when nothing moves on screen), and afterwards the image: the beauty layer and the
// G-buffer's AOVs read back.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/image.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/methods/frame_method.h"
#include "runtime/passes/encode_display_pass.h"

namespace hmb {

class FramePlan;

namespace passes {
class GBufferStage;
struct PostProcessSettings;
}

// The image a raster method shows: its own linear RGBA image, or the G-buffer's colour (packed
// in its samples) where nothing is blurred.
struct Beauty {
  const vk::Buffer* buffer = nullptr;
  passes::DisplaySource source = passes::DisplaySource::LinearRgba;
};
Beauty linearBeauty(const vk::Buffer& linear);
Beauty gbufferBeauty(const passes::GBufferStage& gbuffer);

// A float layer of `values`' first channels.
io::ImageLayer vec4Layer(const std::string& name, std::vector<std::string> channels,
                         const std::vector<glm::vec4>& values);

// A linear RGBA image of the requested size on the device (a method's beauty layer).
vk::Buffer linearImageBuffer(const FrameResources& resources, const FrameRequest& request, std::string name);

// An image of the beauty layer alone (methods without a G-buffer): `linear`'s RGBA.
io::LayeredImage beautyImage(const FrameRequest& request, const vk::Buffer& linear);

// The scene at the request's frame time, the texture path kept when every pass must run, the
// G-buffer prepared and its passes entered in the plan.
// blur: the frame's blur settings (null for a sharp frame); still: nothingMovesOnScreen(request).
// When the blur follows curved paths and the frame is not still, the G-buffer also holds each
// pixel's path over the blur's shutter (a time slice's, with time slices).
GpuScene prepareRasterFrame(FrameResources& resources, const FrameRequest& request, RenderResult& result,
                            const passes::PostProcessSettings* blur = nullptr, bool still = false);

// With nothing moving on screen every velocity is 0: the gather returns each pixel's own colour
// and the hybrid's mask is empty, so the blur's passes are left out.
bool nothingMovesOnScreen(const FrameRequest& request);

// Enters the blur's passes (planned in `blurPlan`) in the frame's plan; all skipped when still.
void planBlur(FramePlan& plan, const FramePlan& blurPlan, bool still);

// The G-buffer's passes, the method's own (`recordMethodPasses`), then the display encoding of
// `beauty`; recorded again with grown buffers while the rasterizer overflows.
vk::FrameTimings recordRasterFrame(FrameResources& resources, const FrameRequest& request, const GpuScene& scene,
                                   const Beauty& beauty,
                                   const std::function<void(vk::FrameRecorder&)>& recordMethodPasses);

// After the frame: beauty (the image the method made) and the G-buffer's depth, normal,
// velocity and object id as the image's layers, with the G-buffer's bytes per pixel and the
// rasterizer's statistics.
void collectRasterFrame(FrameResources& resources, const FrameRequest& request, const Beauty& beauty,
                        RenderResult& result);

}  // namespace hmb
