// The library as an engine's motion-blur backend: post-process (EngineMotionBlur) or hybrid
// (EngineHybridMotionBlur) motion blur recorded into a command buffer the engine owns and
// submits, from the engine's own G-buffer (its images, EngineGBufferImages, or buffers) to an
// output image or buffer the engine gives, on the engine's device (an EngineContext made from
// an EngineVulkan: the engine's instance, device and queue). Recording reads nothing back and
// waits for nothing; the device times of the passes are there once the engine's submission
// completed.
//
// Lifetimes, queues and threads:
//   - An engine object borrows its EngineContext, and the hybrid its scene::Scene (an
//     EngineScene's scene() too): both must outlive it. The hybrid reads the scene in prepare()
//     only; the engine may change it between frames, never during prepare(). Each object owns
//     everything else it made (kernels, buffers, trees) and frees it when destroyed, after
//     waiting for the device to be idle.
//   - record() only records into the engine's command buffer; the engine submits it, to a
//     queue of the context's queue family, and keeps the images and buffers it named alive
//     until that submission completed. EngineMotionBlur holds per-frame buffers alone: keep one
//     per frame in flight. EngineHybridMotionBlur takes the number of frames in flight and
//     cycles through that many sets of per-frame buffers, sharing the meshes' trees: the frame
//     recorded framesInFlight frames earlier must have completed before the next record().
//   - prepare() (the hybrid's setup: new trees) and construction may submit on the queue the
//     context adopted and wait on a fence of their own for that work alone. Vulkan asks a
//     queue's submissions to be externally synchronized: no other thread may submit to that
//     queue meanwhile.
//   - A context and the objects made on it share its command pool: use them from one thread at
//     a time (a context per thread records in parallel). Compiled kernels are shared through a
//     locked cache.
//
// The engine's buffers (storage-buffer usage; one entry per pixel, index y * width + x, row 0 at
// the top of the image):
//   colour    vec4 (16 bytes): linear RGB; alpha is ignored
//   depth     float: as EngineDepth says
//   velocity  vec2 (8 bytes): the pixel's screen motion over the last frame, in pixels, its
//             position now minus its position one frame (1 / fps) earlier, +x right, +y down
//             (the background's too: a turning camera moves it)
//   normal    vec4: world-space normal in xyz (w ignored); the hybrid's edge mask reads it
//   objectId  uint: the object each pixel sees, 0 for the background; the hybrid's objects are
//             its scene's (scene::Instance::objectId)
//   output    vec4: the blurred linear colour, alpha 1
// The blur spreads each pixel along its velocity over the exposure (EngineBlurSettings:
// exposure and fps give the share of a frame the shutter is open; softZExtent is in the
// engine's camera-space depth units).
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "hmblur/hybrid_settings.h"
#include "hmblur/post_process_settings.h"

namespace hmb {

class FramePlan;

namespace vk {
class Context;
struct AdoptedVulkan;
struct ContextOptions;
}
namespace passes {
class HitShading;
}
namespace scene {
struct Scene;
}

// The engine API's names for the library's types it takes (include hmblur/context.h and
// hmblur/hit_shading.h to make them; <hmblur/hmblur.h> has all).
using EngineVulkan = vk::AdoptedVulkan;           // the engine's instance, device, queue and features
using EngineContext = vk::Context;                // EngineContext(EngineVulkan, EngineContextOptions)
using EngineContextOptions = vk::ContextOptions;  // validation and limits to pretend (tests)
using EngineBlurSettings = passes::PostProcessSettings;
using EngineHybridSettings = passes::HybridSettings;
using EngineShading = passes::HitShading;  // the engine's shadeHit and shadeMiss

// The settings the renderer derives for `scene` drawn at width x height: its shutter (fps and
// exposure), SOFT_Z_EXTENT, the tile size for the image's height; the hybrid's also its ray
// mask's and reveal's. shutterRays: the project's extension (hybrid-rays) in place of the
// paper's reveal. Throws hmb::Error in one line for a size of 0.
EngineBlurSettings engineBlurSettingsFor(const scene::Scene& scene, uint32_t width, uint32_t height);
EngineHybridSettings engineHybridSettingsFor(const scene::Scene& scene, uint32_t width, uint32_t height,
                                             bool shutterRays = false);

// How the engine's depth buffer holds depth.
struct EngineDepth {
  enum class Convention {
    CameraSpace,  // distance along the view axis, > 0 ahead of the camera
    StandardZ,    // perspective z/w in [0, 1]: 0 at near, 1 at far
    ReversedZ,    // perspective z/w in [0, 1]: 1 at near, 0 at far (far may be infinite)
  };
  Convention convention = Convention::CameraSpace;
  float near = 0.0f;  // the projection's planes, for the z/w conventions
  float far = std::numeric_limits<float>::infinity();
};

// The device time of a frame's passes, each pass named once. A pass's time runs from the end of
// the pass before (the frame's start for the first: once the engine's earlier commands
// finished) to its own end, so the passes add up to the frame.
struct EnginePassTime {
  std::string name;
  uint32_t runs = 1;          // how often it ran in the frame (one tree level, one bounce, ...)
  double milliseconds = 0.0;  // all its runs together
};
struct EngineFrameTimes {
  std::vector<EnginePassTime> passes;  // in the order each first ran
  double frameMilliseconds = 0.0;
  // Why there are no times (the queue writes no timestamps); empty when there are.
  std::string unavailable;
  bool available() const { return unavailable.empty(); }
};

// The G-buffer as buffers (for compute-only devices, or an engine that keeps them so).
struct EngineGBuffer {
  VkBuffer color = VK_NULL_HANDLE;
  VkBuffer depth = VK_NULL_HANDLE;
  VkBuffer velocity = VK_NULL_HANDLE;
  VkBuffer normal = VK_NULL_HANDLE;    // the hybrid's; the post-process reads it when given
  VkBuffer objectId = VK_NULL_HANDLE;  // likewise
};

// One of the engine's images: a 2D view of one mip level and one layer, its format, and the
// layout the image is in when the recorded frame runs (the engine's transitions put it there;
// the library changes no layout). The G-buffer's views need sampled usage and a layout a
// shader may read (SHADER_READ_ONLY_OPTIMAL, GENERAL, or for depth DEPTH_READ_ONLY_OPTIMAL or
// DEPTH_STENCIL_READ_ONLY_OPTIMAL); the output's storage usage and GENERAL.
struct EngineImage {
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageLayout layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
};

// The G-buffer as the engine's own images, read in place (no copies), each pixel at (x, y) with
// row 0 at the top, in the formats engines draw them:
//   color     any float, UNORM or SNORM format (RGBA16F, B10G11R11 UFLOAT, RGBA8 UNORM, ...): linear RGB
//   depth     a depth format's depth view (D32, D24, D16), or a float format (R32F): as
//             EngineDepth says
//   velocity  a two-channel float format (RG16F, RG32F): the screen motion over the last frame
//             as `velocityUnits` says, position now minus one frame earlier, +x right, +y down
//   normal    world-space normal as `normalEncoding` says: xyz in RGBA16F/RGBA32F, xyz * 0.5 + 0.5
//             in A2B10G10R10 UNORM, or octahedral in RG16 SNORM (or RG16F), or octahedral * 0.5
//             + 0.5 in RG16 UNORM; the hybrid's (the post-process reads it when given)
//   objectId  an unsigned-integer format (R32_UINT, R16_UINT): 0 for the background; likewise
struct EngineGBufferImages {
  EngineImage color, depth, velocity, normal, objectId;
  enum class VelocityUnits {
    Pixels,  // pixels per frame
    Ndc,     // Vulkan normalized device coordinates per frame: [-1, 1] across the image, +y down
  };
  VelocityUnits velocityUnits = VelocityUnits::Pixels;
  enum class NormalEncoding { Xyz, XyzUnorm, Octahedral, OctahedralUnorm };
  NormalEncoding normalEncoding = NormalEncoding::Xyz;
};
// The output image's formats: R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT (a storage image's
// format is its shader's), linear RGB, alpha 1.

class EngineMotionBlur {
 public:
  // Validates the settings and the depth convention (hmb::Error, one line) and builds the kernels.
  EngineMotionBlur(const EngineContext& context, uint32_t width, uint32_t height, const EngineBlurSettings& settings,
                   EngineDepth depth = {});
  ~EngineMotionBlur();
  EngineMotionBlur(const EngineMotionBlur&) = delete;
  EngineMotionBlur& operator=(const EngineMotionBlur&) = delete;

  // Records the blur into `commandBuffer` (recording, outside a render pass, for a queue of the
  // context's family): a barrier after the engine's earlier writes, the passes, and a barrier
  // before its later commands. The frame recorded before must have completed on the device
  // (keep one EngineMotionBlur per frame in flight).
  void record(VkCommandBuffer commandBuffer, const EngineGBuffer& gbuffer, VkBuffer output);
  // The same from the engine's images into its output image.
  void record(VkCommandBuffer commandBuffer, const EngineGBufferImages& gbuffer, const EngineImage& output);

  // The device time of the last recorded frame's passes, once the engine's submission of it
  // completed.
  EngineFrameTimes timings() const;

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  struct Passes;
  const vk::Context& context_;
  uint32_t width_, height_;
  EngineDepth depth_;
  std::unique_ptr<Passes> passes_;
};

// The hybrid method on an engine's frame: the post-process blur of the engine's G-buffer, with
// the background hidden behind moving objects ray traced inside the ray mask (the paper's
// method, passes::HybridStage). The rays need the engine's geometry: a scene::Scene (meshes,
// materials, instances with their object ids and motion, and the camera that drew the
// G-buffer), which must outlive this object. An engine that keeps matrices, not animation,
// gives EngineScene::scene() and sets each frame's transforms there before prepare().
class EngineHybridMotionBlur {
 public:
  // hits: how revealed surfaces are shaded (null or the library's: the scene's materials).
  EngineHybridMotionBlur(const EngineContext& context, uint32_t width, uint32_t height, const scene::Scene& scene,
                         const EngineHybridSettings& settings, EngineDepth depth = {},
                         const EngineShading* hits = nullptr, uint32_t framesInFlight = 1);
  // framesInFlight (1 to kMaxFramesInFlight): how many recorded frames may be on the device at
  // once. Each prepare()/record() pair takes the next of that many sets of per-frame buffers;
  // the meshes' trees and the scene's vertices, materials and textures are made once and
  // shared by all (a deforming scene's vertices and trees are per frame: each frame changes them).
  static constexpr uint32_t kMaxFramesInFlight = 8;
  uint32_t framesInFlight() const;
  ~EngineHybridMotionBlur();
  EngineHybridMotionBlur(const EngineHybridMotionBlur&) = delete;
  EngineHybridMotionBlur& operator=(const EngineHybridMotionBlur&) = delete;

  // Before recording the frame at frameTime (seconds, the scene's clock): plans the frame
  // (which trees to build or keep) and computes all its transforms and its camera on the host,
  // from the scene as it is now (record() reads the scene no more). Only setup waits, and
  // prepare() returns its device time: where the meshes are new (the first frame, or an
  // EngineScene given other meshes) it builds their trees; the first frame after that which
  // refits deforming meshes prepares the refit; a split top level's still instances' tree is
  // built when those instances change. Any other frame waits for nothing.
  EngineFrameTimes prepare(float frameTime);
  // Records the frame prepare() was last given into `commandBuffer`, as EngineMotionBlur
  // records (the G-buffer's normal and objectId are required here), never submitting or
  // waiting: the frame's transforms, camera and joints (written through the command buffer),
  // the deforming meshes' vertices and their trees' refit, the instances' tree where they
  // moved, then the hybrid's passes.
  void record(VkCommandBuffer commandBuffer, const EngineGBuffer& gbuffer, VkBuffer output);
  void record(VkCommandBuffer commandBuffer, const EngineGBufferImages& gbuffer, const EngineImage& output);
  EngineFrameTimes timings() const;

  // After the frame completed, read back on request: the ray mask's pixels (none beside
  // shutter rays: settings' shutterRays), the pixels that took shutter rays, and the traces the
  // device's loop limit cut short (Mesa 22.3's lavapipe: RenderResult::cutTraces), whose pixels
  // may be wrong.
  uint32_t maskPixels() const;
  uint32_t shutterRayPixels() const;
  uint32_t cutTraces() const;
  // The last prepare()'s plan: which trees it built or kept (and why), and the frame's passes.
  const FramePlan& plan() const;

 private:
  struct Passes;
  void recorded();  // the prepared frame was recorded: the next prepare() takes the next set
  const vk::Context& context_;
  uint32_t width_, height_;
  const scene::Scene& scene_;
  passes::HybridSettings settings_;
  EngineDepth depth_;
  std::unique_ptr<Passes> passes_;
  bool prepared_ = false;
};

}  // namespace hmb
