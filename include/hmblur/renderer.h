// The library API: a renderer on a chosen device renders a scene with a method and hands back
// the images, the frame plan and the timings. The CLI uses nothing else.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hmblur/frame_plan.h"
#include "hmblur/frame_timings.h"
#include "hmblur/hybrid_settings.h"
#include "hmblur/image.h"
#include "hmblur/method.h"
#include "hmblur/post_process_settings.h"
#include "hmblur/raster_scheme.h"
#include "hmblur/reference_settings.h"
#include "hmblur/scene.h"

namespace hmb::vk {
class Context;
}

namespace hmb {

// The largest image side accepted; larger requests fail before any allocation.
inline constexpr uint32_t kMaxImageSide = 16384;

struct RenderSettings {
  Method method = Method::Sharp;
  uint32_t width = 1280;
  uint32_t height = 720;
  std::optional<float> frameTime;  // seconds; default: the scene's settings.frameTime
  // What the user chose of each method's settings (the rest derive from the scene and the image).
  passes::ReferenceSettings reference;
  passes::PostProcessChoices postprocess;  // postprocess, and the hybrid's blur
  passes::HybridChoices hybrid;
  // Leave out the passes that cannot change the image (the plan lists them as skipped, with
  // why); false runs every pass, to check that leaving them out changes nothing.
  bool skipUnneededPasses = true;
  // Keep what the last render built that still serves this frame (the hybrid's mesh trees for
  // the same meshes, its top-level tree when no instance moved). A benchmark that renders one
  // frame over and over turns this off, so each repeat pays what a new frame of an animation
  // does. Off as well when skipUnneededPasses is.
  bool reuseAcrossFrames = true;
  // Long methods (the reference) report how far they are after every submission.
  std::function<void(const passes::ReferenceProgress&)> onProgress;
};

struct RenderResult {
  Method method = Method::Sharp;
  RenderSettings settings;  // what it was rendered with (the progress callback left out)
  uint32_t width = 0;
  uint32_t height = 0;
  float frameTime = 0.0f;
  io::LayeredImage image;    // linear beauty + AOV layers
  io::Rgba8Image display;    // the display transform of the beauty layer
  FramePlan plan;
  std::optional<double> frameMilliseconds;
  // What the frame asked of the device and the host (dispatches, barriers, host waits, the
  // longest chain of dependent dispatches), scene setup left out as from its time; and the
  // setup's own where this render made one (the hybrid's mesh trees).
  vk::FrameShape frameShape;
  std::optional<vk::FrameShape> setupShape;
  // Device memory (every vk::Buffer of the context): the most held at once during the render,
  // the G-buffer's bytes per pixel, and (hybrid) the mesh trees' bytes per mesh triangle as
  // allocated (for the worst case) and as built.
  struct Memory {
    uint64_t peakBytes = 0;
    double gbufferBytesPerPixel = 0;
    std::optional<double> bvhAllocatedBytesPerTriangle, bvhBuiltBytesPerTriangle;
  };
  Memory memory;
  // The G-buffer rasterizer of the frame (methods without one leave these empty).
  std::string visibilityScheme;
  passes::RasterStats raster;
  // The post-process methods: the settings they ran with.
  std::optional<passes::PostProcessSettings> postprocess;
  // The hybrid methods: their settings, the ray mask's size and the reveal's rays (hybrid), the
  // shutter rays' pixels and rays (hybrid-rays).
  struct Hybrid {
    passes::HybridSettings settings;
    uint64_t edgeCandidates = 0;  // pixels whose end lies on a deeper object (eqs. 1-2)
    uint64_t rangeBlocks = 0;     // 8 x 8 blocks the range check walked (an edge within reach)
    uint64_t maskPixels = 0;
    uint64_t revealedPixels = 0;  // mask pixels whose composite needs the background, traced
    uint64_t revealRays = 0;
    uint64_t shutterRayPixels = 0;        // pixels whose path crosses an edge, listed for shutter rays
    uint64_t shutterRayPixelsTraced = 0;  // those traced: every one, or under a ray budget the ones kept
    uint64_t shutterRays = 0;             // rays traced
    std::optional<double> setupMilliseconds;  // the trace scene's mesh trees: per scene, not per frame
  };
  std::optional<Hybrid> hybrid;
  // The reference: samples per pixel in the image (resumed ones included).
  std::optional<passes::ReferenceProgress> reference;
  // The methods that trace: the traces the device's loop limit cut short (Mesa 22.3's lavapipe
  // ends every loop of an invocation after 65535 rounds in all), whose pixels may be wrong.
  uint64_t cutTraces = 0;
};

// The names of the methods the demo renders, in its order (include/hmblur/method.h has them all).
std::vector<std::string> methodNames();

// Every setting a user can choose for a render, for front ends: one per name across the
// post-process, hybrid and reference tables (a name in several tables, like seed, reads into
// each). Built from the tables' descriptions; the help text ends with the methods that read
// the setting, the values it accepts and its default.
struct RenderSettingDescription {
  std::string name;
  std::string help;
  std::string valueName;  // "N", "X", "NAME", "FILE"
  bool flag = false;      // a switch without a value
  std::vector<Method> methods;  // the methods it is a setting of
  // The text a user typed into the settings' choices (throws hmb::Error naming the setting).
  std::function<void(RenderSettings&, std::string_view text)> read;
};
std::vector<RenderSettingDescription> renderSettingDescriptions();

// The post-process settings of a render of this scene: the scene's, the image's tile sizes and
// the user's choices (throws hmb::Error naming the first absurd value).
passes::PostProcessSettings postProcessSettingsFor(const scene::Scene& scene, const RenderSettings& settings);

// The hybrid settings of a render of this scene, its blur included (throws hmb::Error).
passes::HybridSettings hybridSettingsFor(const scene::Scene& scene, const RenderSettings& settings);

// Throw hmb::Error (one line) for choices no scene could take: the choices over the defaults.
void validatePostProcessChoices(const RenderSettings& settings);
void validateHybridChoices(const RenderSettings& settings);

// Throws hmb::Error (one line) for an unusable size or settings the method cannot render with.
void validateRenderSettings(const RenderSettings& settings);

struct FrameResources;
class FrameMethod;

// Renders frames with any method on one device. It owns what the methods share (the G-buffer,
// the post-process blur, the display encoding, the frame recorder) and each method's
// FrameMethod, made on its first frame and kept with what it keeps across frames.
// How a Renderer is built for its device (every choice has a default from the device).
struct RendererOptions {
  // The G-buffer rasterizer's visibility scheme; default: passes::defaultVisibilityScheme
  // (tile lists on CPU devices, 64-bit atomics on GPUs that have them, else 32-bit two-pass).
  std::optional<passes::VisibilityScheme> visibilityScheme;
  // The shading of rays in the hybrid's reveal and shutter rays and the reference's samples:
  // empty, the library's; else the GLSL of `vec3 shadeHit(HitRecord hit)` and of
  // `vec3 shadeMiss(vec3 direction)` for rays that hit nothing (passes::HitShading,
  // hmblur/hit_shading.glsl), compiled into those kernels at the first render that needs them
  // (a compile error is a one-line hmb::Error). The raster's G-buffer keeps the library's.
  std::string shadeHit;
  std::string shadeMiss;
};

class Renderer {
 public:
  explicit Renderer(vk::Context& context, RendererOptions options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // One frame of `scene` with the settings' method. Post-process and hybrid with time-slices
  // K > 1 render K frames, each over its slice of the shutter, and return their mean.
  RenderResult render(const scene::Scene& scene, const RenderSettings& settings);

 private:
  RenderResult renderFrame(const scene::Scene& scene, const RenderSettings& settings);
  RenderResult renderTimeSlices(const scene::Scene& scene, const RenderSettings& settings, uint32_t slices);
  struct Shared;
  FrameMethod& methodFor(Method method);

  vk::Context& context_;
  RendererOptions options_;
  std::unique_ptr<Shared> shared_;  // pipelines are created once, on first use
};

}  // namespace hmb
