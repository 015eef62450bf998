#include "hmblur/engine_motion_blur.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <string>

#include <glm/glm.hpp>

#include "hmblur/buffer.h"
#include "hmblur/context.h"
#include "hmblur/error.h"
#include "hmblur/frame_plan.h"
#include "hmblur/frame_timings.h"
#include "hmblur/renderer.h"
#include "kernels/engine/engine_layout.h"
#include "kernels/manifest.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/device_scene/trace_scene.h"
#include "runtime/passes/hybrid_stage.h"
#include "runtime/passes/image_layer.h"
#include "runtime/passes/post_process_stage.h"
#include "runtime/vulkan/compute_kernel.h"

namespace hmb {
namespace {

constexpr const char* kPackPass = "pack-engine-gbuffer";
constexpr const char* kWriteOutputPass = "write-engine-output";

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

gpu::EngineGBufferParams packParams(uint32_t width, uint32_t height, const EngineDepth& depth) {
  gpu::EngineGBufferParams params{};
  params.width = width;
  params.height = height;
  params.depthConvention = conventionCode(depth.convention);
  params.near = depth.near;
  params.far = depth.far;
  return params;
}

// pack-engine-gbuffer with or without the engine's normals and object ids.
std::unique_ptr<vk::ComputeKernel> packKernel(const vk::Context& context, bool surfaces) {
  std::array<uint32_t, HMB_SPEC_ENGINE_SURFACES + 1> specialization{};
  specialization[HMB_SPEC_ENGINE_SURFACES] = surfaces ? 1u : 0u;  // VkBool32
  return std::make_unique<vk::ComputeKernel>(context, kernels::kernel("engine/pack_engine_gbuffer"),
                                             specialization);
}

// Binds the engine's buffers (not owned: adopted for the frame's descriptors) and records
// pack-engine-gbuffer into `layer` with `pack`, the build for whether normals and ids are
// given. Without them, the kernel's two bindings for them take the colour and depth buffers,
// which that build does not read.
void recordPack(vk::FrameRecorder& frame, const vk::Context& context, const vk::ComputeKernel& pack,
                const EngineGBuffer& g, uint32_t width, uint32_t height, const EngineDepth& depth,
                const passes::ImageLayer& layer) {
  const uint64_t pixels = uint64_t(width) * height;
  const vk::Buffer color = vk::Buffer::adopt(context, g.color, pixels * sizeof(glm::vec4), "engine colour");
  const vk::Buffer z = vk::Buffer::adopt(context, g.depth, pixels * sizeof(float), "engine depth");
  const vk::Buffer velocity = vk::Buffer::adopt(context, g.velocity, pixels * sizeof(glm::vec2), "engine velocity");
  const bool surfaces = g.normal && g.objectId;  // as `pack` was built
  const vk::Buffer normal =
      vk::Buffer::adopt(context, surfaces ? g.normal : g.color, pixels * sizeof(glm::vec4), "engine normal");
  const vk::Buffer objectId =
      vk::Buffer::adopt(context, surfaces ? g.objectId : g.depth, pixels * sizeof(uint32_t), "engine object id");
  frame.dispatch(kPackPass, pack,
                 {{HMB_ENGINE_BINDING_COLOR, &color},
                  {HMB_ENGINE_BINDING_DEPTH, &z},
                  {HMB_ENGINE_BINDING_VELOCITY, &velocity},
                  {HMB_ENGINE_BINDING_SAMPLES, &layer.samples()},
                  {HMB_ENGINE_BINDING_SURFACES, &layer.surfaces()},
                  {HMB_ENGINE_BINDING_NORMAL, &normal},
                  {HMB_ENGINE_BINDING_OBJECT_ID, &objectId},
                  {HMB_ENGINE_BINDING_VELOCITIES, &layer.velocities()}},
                 packParams(width, height, depth),
                 {vk::groupsFor(width, HMB_ENGINE_GROUP_X), vk::groupsFor(height, HMB_ENGINE_GROUP_Y), 1});
}

// What a format's texels read as in a shader.
enum class FormatKind { Undefined, Float, UnsignedInt, SignedInt, Depth };

FormatKind formatKind(VkFormat format) {
  switch (format) {
    case VK_FORMAT_UNDEFINED: return FormatKind::Undefined;
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return FormatKind::Depth;
    case VK_FORMAT_R8_UINT:
    case VK_FORMAT_R8G8_UINT:
    case VK_FORMAT_R8G8B8A8_UINT:
    case VK_FORMAT_B8G8R8A8_UINT:
    case VK_FORMAT_A2B10G10R10_UINT_PACK32:
    case VK_FORMAT_A2R10G10B10_UINT_PACK32:
    case VK_FORMAT_R16_UINT:
    case VK_FORMAT_R16G16_UINT:
    case VK_FORMAT_R16G16B16A16_UINT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32B32_UINT:
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_S8_UINT: return FormatKind::UnsignedInt;
    case VK_FORMAT_R8_SINT:
    case VK_FORMAT_R8G8_SINT:
    case VK_FORMAT_R8G8B8A8_SINT:
    case VK_FORMAT_R16_SINT:
    case VK_FORMAT_R16G16_SINT:
    case VK_FORMAT_R16G16B16A16_SINT:
    case VK_FORMAT_R32_SINT:
    case VK_FORMAT_R32G32_SINT:
    case VK_FORMAT_R32G32B32_SINT:
    case VK_FORMAT_R32G32B32A32_SINT: return FormatKind::SignedInt;
    default: return FormatKind::Float;
  }
}

// One line naming the image and what is wrong, or nothing.
void checkImage(const EngineImage& image, const char* what, FormatKind wanted, const char* wantedText, bool output) {
  const std::string name = std::string("engine image '") + what + "'";
  if (!image.view) throw Error(name + ": no image view");
  if (formatKind(image.format) != wanted)
    throw Error(name + ": its format (VkFormat " + std::to_string(int(image.format)) + ") is not " + wantedText);
  const VkImageLayout l = image.layout;
  if (output) {
    if (l != VK_IMAGE_LAYOUT_GENERAL) throw Error(name + ": a storage image is written in VK_IMAGE_LAYOUT_GENERAL");
    return;
  }
  const bool readable = l == VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_GENERAL ||
                        (wanted == FormatKind::Depth && (l == VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL ||
                                                         l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL ||
                                                         l == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL));
  if (!readable) throw Error(name + ": its layout is not one a shader reads (SHADER_READ_ONLY_OPTIMAL, GENERAL"
                                     ", or a depth read-only layout)");
}

// The images path: pack-engine-gbuffer reading the engine's images, the frame's colour in a
// buffer of its own, and write-engine-output carrying it into the engine's output image.
class EngineImageIo {
 public:
  explicit EngineImageIo(const vk::Context& context) : context_(context) {}

  // Checks the images, one line for the first wrong one, before anything is recorded.
  static void check(const EngineGBufferImages& g, bool surfaces, const EngineImage& output) {
    checkImage(g.color, "color", FormatKind::Float, "a float, UNORM or SNORM format", false);
    // A depth attachment's depth view, or a float target holding (camera-space) depth.
    const FormatKind depthKind = formatKind(g.depth.format) == FormatKind::Float ? FormatKind::Float : FormatKind::Depth;
    checkImage(g.depth, "depth", depthKind, "a depth format or a float format", false);
    checkImage(g.velocity, "velocity", FormatKind::Float, "a float format", false);
    if (surfaces) {
      checkImage(g.normal, "normal", FormatKind::Float, "a float, UNORM or SNORM format", false);
      checkImage(g.objectId, "objectId", FormatKind::UnsignedInt, "an unsigned-integer format", false);
    }
    checkImage(output, "output", FormatKind::Float, "R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT", true);
    if (output.format != VK_FORMAT_R16G16B16A16_SFLOAT && output.format != VK_FORMAT_R32G32B32A32_SFLOAT)
      throw Error("engine image 'output': its format (VkFormat " + std::to_string(int(output.format)) +
                  ") is not R16G16B16A16_SFLOAT or R32G32B32A32_SFLOAT");
  }

  // Records the pack of images check() accepted.
  void recordPack(vk::FrameRecorder& frame, const EngineGBufferImages& g, bool surfaces, uint32_t width,
                  uint32_t height, const EngineDepth& depth, const passes::ImageLayer& layer) {
    std::unique_ptr<vk::ComputeKernel>& kernel = surfaces ? packWithSurfaces_ : pack_;
    if (!kernel)
      kernel = std::make_unique<vk::ComputeKernel>(
          context_, surfaces ? kernels::kernel("engine/pack_engine_images")
                             : kernels::kernel("engine/pack_engine_colour_images"));
    gpu::EngineGBufferParams params = packParams(width, height, depth);
    params.velocityUnits = g.velocityUnits == EngineGBufferImages::VelocityUnits::Ndc ? HMB_ENGINE_VELOCITY_NDC
                                                                                      : HMB_ENGINE_VELOCITY_PIXELS;
    params.normalEncoding = normalCode(g.normalEncoding);
    vk::Bindings bindings = {{HMB_ENGINE_BINDING_COLOR, nullptr, g.color.view, g.color.layout},
                             {HMB_ENGINE_BINDING_DEPTH, nullptr, g.depth.view, g.depth.layout},
                             {HMB_ENGINE_BINDING_VELOCITY, nullptr, g.velocity.view, g.velocity.layout},
                             {HMB_ENGINE_BINDING_SAMPLES, &layer.samples()},
                             {HMB_ENGINE_BINDING_SURFACES, &layer.surfaces()},
                             {HMB_ENGINE_BINDING_VELOCITIES, &layer.velocities()}};
    if (surfaces) {
      bindings.push_back({HMB_ENGINE_BINDING_NORMAL, nullptr, g.normal.view, g.normal.layout});
      bindings.push_back({HMB_ENGINE_BINDING_OBJECT_ID, nullptr, g.objectId.view, g.objectId.layout});
    }
    frame.dispatch(kPackPass, *kernel, bindings, params,
                   {vk::groupsFor(width, HMB_ENGINE_GROUP_X), vk::groupsFor(height, HMB_ENGINE_GROUP_Y), 1});
  }

  // The frame's colour before it goes into the output image (made on first use).
  const vk::Buffer& colour(uint32_t width, uint32_t height) {
    if (!colour_.handle())
      colour_ = vk::Buffer(context_, uint64_t(width) * height * sizeof(glm::vec4), vk::MemoryUse::Device,
                           "engine output colour");
    return colour_;
  }

  void recordOutput(vk::FrameRecorder& frame, const EngineImage& output, uint32_t width, uint32_t height) {
    const bool half = output.format == VK_FORMAT_R16G16B16A16_SFLOAT;
    std::unique_ptr<vk::ComputeKernel>& kernel = half ? writeHalf_ : writeFloat_;
    if (!kernel)
      kernel = std::make_unique<vk::ComputeKernel>(
          context_, half ? kernels::kernel("engine/write_output_rgba16f") : kernels::kernel("engine/write_output_rgba32f"));
    const gpu::EngineOutputParams params{width, height, 0u, 0u};
    frame.dispatch(kWriteOutputPass, *kernel,
                   {{HMB_ENGINE_OUTPUT_BINDING_COLOR, &colour_},
                    {HMB_ENGINE_OUTPUT_BINDING_IMAGE, nullptr, output.view, output.layout}},
                   params, {vk::groupsFor(width, HMB_ENGINE_GROUP_X), vk::groupsFor(height, HMB_ENGINE_GROUP_Y), 1});
  }

 private:
  static uint32_t normalCode(EngineGBufferImages::NormalEncoding encoding) {
    switch (encoding) {
      case EngineGBufferImages::NormalEncoding::XyzUnorm: return HMB_ENGINE_NORMAL_XYZ_UNORM;
      case EngineGBufferImages::NormalEncoding::Octahedral: return HMB_ENGINE_NORMAL_OCTAHEDRAL;
      case EngineGBufferImages::NormalEncoding::OctahedralUnorm: return HMB_ENGINE_NORMAL_OCTAHEDRAL_UNORM;
      case EngineGBufferImages::NormalEncoding::Xyz: break;
    }
    return HMB_ENGINE_NORMAL_XYZ;
  }

  const vk::Context& context_;
  std::unique_ptr<vk::ComputeKernel> pack_, packWithSurfaces_, writeHalf_, writeFloat_;
  vk::Buffer colour_;
};

// The recorder's per-run times, each pass named once.
EngineFrameTimes engineTimes(const vk::FrameTimings& timings) {
  EngineFrameTimes times;
  if (!timings.frameMilliseconds && !timings.passes.empty()) {
    times.unavailable = "the device's queue writes no timestamps";
    return times;
  }
  times.frameMilliseconds = timings.frameMilliseconds.value_or(0.0);
  for (const vk::PassTiming& pass : timings.passes) {
    auto same = std::find_if(times.passes.begin(), times.passes.end(),
                             [&](const EnginePassTime& p) { return p.name == pass.name; });
    if (same == times.passes.end()) {
      times.passes.push_back({pass.name, 1, pass.milliseconds.value_or(0.0)});
    } else {
      ++same->runs;
      same->milliseconds += pass.milliseconds.value_or(0.0);
    }
  }
  return times;
}

// The render settings the engine's settings are derived from.
RenderSettings renderSettingsAt(uint32_t width, uint32_t height, Method method) {
  if (width == 0 || height == 0) throw Error("engine settings: an empty image");
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.method = method;
  return settings;
}

}  // namespace

EngineBlurSettings engineBlurSettingsFor(const scene::Scene& scene, uint32_t width, uint32_t height) {
  return postProcessSettingsFor(scene, renderSettingsAt(width, height, Method::PostProcess));
}

EngineHybridSettings engineHybridSettingsFor(const scene::Scene& scene, uint32_t width, uint32_t height,
                                             bool shutterRays) {
  return hybridSettingsFor(scene,
                           renderSettingsAt(width, height, shutterRays ? Method::HybridRays : Method::Hybrid));
}

struct EngineMotionBlur::Passes {
  Passes(const vk::Context& context, uint32_t width, uint32_t height, const passes::PostProcessSettings& settings)
      : pack(packKernel(context, false)),
        blur(context, settings),
        layer(passes::ImageLayer::allocate(context, uint64_t(width) * height, "engine G-buffer")),
        recorder(context),
        images(context) {
    blur.prepare(width, height);
  }
  std::unique_ptr<vk::ComputeKernel> pack;              // without normals and ids
  std::unique_ptr<vk::ComputeKernel> packWithSurfaces;  // made when a frame first gives them
  passes::PostProcessStage blur;
  passes::ImageLayer layer;
  vk::FrameRecorder recorder;
  EngineImageIo images;
};

EngineMotionBlur::EngineMotionBlur(const vk::Context& context, uint32_t width, uint32_t height,
                                   const passes::PostProcessSettings& settings, EngineDepth depth)
    : context_(context), width_(width), height_(height), depth_(depth) {
  if (width == 0 || height == 0) throw Error("engine motion blur: an empty image");
  validateDepth(depth);
  // An engine's G-buffer has no points at mid-shutter and shutter open to curve a path through.
  if (settings.motionPath != passes::MotionPath::Linear)
    throw Error("engine motion blur: the engine's G-buffer gives straight velocities only (motion-path linear)");
  passes_ = std::make_unique<Passes>(context, width, height, settings);
}

EngineMotionBlur::~EngineMotionBlur() = default;

void EngineMotionBlur::record(VkCommandBuffer commandBuffer, const EngineGBuffer& gbuffer, VkBuffer output) {
  const vk::Buffer blurred =
      vk::Buffer::adopt(context_, output, uint64_t(width_) * height_ * sizeof(glm::vec4), "engine output");
  vk::FrameRecorder& frame = passes_->recorder;
  const passes::ImageLayer& layer = passes_->layer;
  const bool surfaces = gbuffer.normal && gbuffer.objectId;
  if (surfaces && !passes_->packWithSurfaces) passes_->packWithSurfaces = packKernel(context_, true);
  frame.beginInto(commandBuffer);
  recordPack(frame, context_, surfaces ? *passes_->packWithSurfaces : *passes_->pack, gbuffer, width_, height_, depth_,
             layer);
  passes_->blur.record(frame, {&layer.samples(), &layer.surfaces(), &layer.velocities(), width_, height_}, blurred);
  frame.endInto();
}

void EngineMotionBlur::record(VkCommandBuffer commandBuffer, const EngineGBufferImages& gbuffer,
                              const EngineImage& output) {
  EngineImageIo& images = passes_->images;
  const bool surfaces = gbuffer.normal.view && gbuffer.objectId.view;
  EngineImageIo::check(gbuffer, surfaces, output);
  const vk::Buffer& colour = images.colour(width_, height_);
  const passes::ImageLayer& layer = passes_->layer;
  vk::FrameRecorder& frame = passes_->recorder;
  frame.beginInto(commandBuffer);
  images.recordPack(frame, gbuffer, surfaces, width_, height_, depth_, layer);
  passes_->blur.record(frame, {&layer.samples(), &layer.surfaces(), &layer.velocities(), width_, height_}, colour);
  images.recordOutput(frame, output, width_, height_);
  frame.endInto();
}

EngineFrameTimes EngineMotionBlur::timings() const { return engineTimes(passes_->recorder.readTimings()); }

struct EngineHybridMotionBlur::Passes {
  // What one frame in flight records into and reads: everything but the mesh trees.
  struct Slot {
    Slot(const vk::Context& context, uint32_t width, uint32_t height, const passes::HybridSettings& settings,
         const passes::HitShading* hits)
        : pack(packKernel(context, true)),
          blur(context, settings.blur),
          hybrid(context, blur, hits),
          layer(passes::ImageLayer::allocate(context, uint64_t(width) * height, "engine G-buffer")),
          setup(context),
          recorder(context),
          images(context) {
      blur.prepare(width, height);
    }
    std::unique_ptr<vk::ComputeKernel> pack;  // with normals and ids: the hybrid needs them
    // The scene's materials, vertices and textures, for shading what rays find (shared with
    // the other sets where the scene does not deform): made again when the scene's meshes or its
    // instances' meshes and ids change (an EngineScene's next frame).
    std::unique_ptr<GpuScene> gpuScene;
    std::vector<glm::uvec2> gpuSceneInstances;  // (mesh, object id) of each instance it was made for
    size_t gpuSceneMeshes = 0;
    GpuScene::FrameInputs frameInputs;  // the last prepare()'s, written by record()
    passes::PostProcessStage blur;
    passes::HybridStage hybrid;
    passes::ImageLayer layer;
    vk::FrameRecorder setup;     // prepare()'s own submissions
    vk::FrameRecorder recorder;  // the engine's command buffer
    FramePlan plan;              // the last prepare()'s
    EngineImageIo images;

    // The prepared frame into the engine's command buffer: its inputs, the G-buffer packed by
    // `pack`, the frame's deformation, the hybrid's passes into `colour`, then `finish`.
    void record(VkCommandBuffer commandBuffer, const std::function<void(vk::FrameRecorder&)>& pack,
                const vk::Buffer& colour, const std::function<void(vk::FrameRecorder&)>& finish) {
      recorder.beginInto(commandBuffer);
      gpuScene->recordFrameInputs(frameInputs, recorder);
      pack(recorder);
      if (gpuScene->deforms()) gpuScene->recordFrameDeformation(recorder);  // what the reveal shades
      hybrid.record(recorder, plan, layer, *gpuScene, colour);
      if (finish) finish(recorder);
      recorder.endInto();
    }
  };
  std::vector<std::unique_ptr<Slot>> slots;
  size_t next = 0;      // the slot the next prepare() plans
  size_t prepared = 0;  // the slot prepare() last planned, which record() records
  size_t recorded = 0;  // the slot record() last recorded: its times and counts

  Slot& preparedSlot() { return *slots[prepared]; }
  const Slot& recordedSlot() const { return *slots[recorded]; }
};

EngineHybridMotionBlur::EngineHybridMotionBlur(const vk::Context& context, uint32_t width, uint32_t height,
                                               const scene::Scene& scene, const passes::HybridSettings& settings,
                                               EngineDepth depth, const passes::HitShading* hits,
                                               uint32_t framesInFlight)
    : context_(context), width_(width), height_(height), scene_(scene), settings_(settings), depth_(depth) {
  if (width == 0 || height == 0) throw Error("engine hybrid motion blur: an empty image");
  if (framesInFlight < 1 || framesInFlight > kMaxFramesInFlight)
    throw Error("engine hybrid motion blur: frames in flight must be 1 to " + std::to_string(kMaxFramesInFlight));
  validateDepth(depth);
  passes::validate(settings);
  if (settings.blur.motionPath != passes::MotionPath::Linear)
    throw Error("engine hybrid motion blur: the engine's G-buffer gives straight velocities only (motion-path linear)");
  passes_ = std::make_unique<Passes>();
  const auto shared = std::make_shared<SharedMeshTrees>();
  for (uint32_t i = 0; i < framesInFlight; ++i) {
    passes_->slots.push_back(std::make_unique<Passes::Slot>(context, width, height, settings, hits));
    if (framesInFlight > 1) passes_->slots.back()->hybrid.shareMeshTrees(shared);
  }
}

EngineHybridMotionBlur::~EngineHybridMotionBlur() = default;

EngineFrameTimes EngineHybridMotionBlur::prepare(float frameTime) {
  if (!std::isfinite(frameTime)) throw Error("engine hybrid motion blur: the frame time must be finite");
  Passes::Slot& slot = *passes_->slots[passes_->next];
  std::vector<glm::uvec2> instances;
  for (const scene::Instance& instance : scene_.instances) instances.emplace_back(instance.mesh, instance.objectId);
  if (!slot.gpuScene || instances != slot.gpuSceneInstances || scene_.meshes.size() != slot.gpuSceneMeshes) {
    slot.gpuScene.reset();  // the old one goes first: the two never take memory at once
    // Another set's scene of the same instances and meshes lends its vertices, materials and
    // textures (a deforming scene's vertices are each frame's own).
    const Passes::Slot* lender = nullptr;
    for (const std::unique_ptr<Passes::Slot>& other : passes_->slots)
      if (other->gpuScene && !other->gpuScene->deforms() && other->gpuSceneInstances == instances &&
          other->gpuSceneMeshes == scene_.meshes.size())
        lender = other.get();
    slot.gpuScene = lender ? std::make_unique<GpuScene>(context_, *lender->gpuScene)
                           : std::make_unique<GpuScene>(context_, scene_);
    slot.gpuSceneInstances = std::move(instances);
    slot.gpuSceneMeshes = scene_.meshes.size();
  }
  // A deforming scene's joints and weights at the frame time and the one before, and the
  // transforms and the camera for shading what the rays find, are computed here on the host;
  // record() writes them, deforms the meshes and refits their trees in the frame.
  if (slot.gpuScene->deforms()) slot.gpuScene->setDeformationFrame(scene_, frameTime);
  slot.frameInputs = GpuScene::frameInputs(scene_, frameTime, width_, height_);
  FramePlan plan;
  plan.run(GpuScene::kFrameInputs);
  plan.run(kPackPass);
  slot.hybrid.plan(plan, scene_, frameTime, settings_);
  const auto timings = slot.hybrid.prepare(slot.setup, scene_, frameTime, width_, height_, settings_, plan);
  slot.plan = plan;
  passes_->prepared = passes_->next;
  prepared_ = true;
  return engineTimes(timings.setup);
}

void EngineHybridMotionBlur::record(VkCommandBuffer commandBuffer, const EngineGBuffer& gbuffer, VkBuffer output) {
  if (!prepared_) throw Error("engine hybrid motion blur: record() before prepare()");
  if (!gbuffer.normal || !gbuffer.objectId)
    throw Error("engine hybrid motion blur: the G-buffer's normal and objectId buffers are required");
  const vk::Buffer blurred =
      vk::Buffer::adopt(context_, output, uint64_t(width_) * height_ * sizeof(glm::vec4), "engine output");
  Passes::Slot& slot = passes_->preparedSlot();
  slot.record(
      commandBuffer,
      [&](vk::FrameRecorder& frame) {
        recordPack(frame, context_, *slot.pack, gbuffer, width_, height_, depth_, slot.layer);
      },
      blurred, {});
  recorded();
}

void EngineHybridMotionBlur::record(VkCommandBuffer commandBuffer, const EngineGBufferImages& gbuffer,
                                    const EngineImage& output) {
  if (!prepared_) throw Error("engine hybrid motion blur: record() before prepare()");
  if (!gbuffer.normal.view || !gbuffer.objectId.view)
    throw Error("engine hybrid motion blur: the G-buffer's normal and objectId images are required");
  EngineImageIo::check(gbuffer, true, output);
  Passes::Slot& slot = passes_->preparedSlot();
  EngineImageIo& images = slot.images;
  slot.record(
      commandBuffer,
      [&](vk::FrameRecorder& frame) { images.recordPack(frame, gbuffer, true, width_, height_, depth_, slot.layer); },
      images.colour(width_, height_),
      [&](vk::FrameRecorder& frame) { images.recordOutput(frame, output, width_, height_); });
  recorded();
}

void EngineHybridMotionBlur::recorded() {
  passes_->recorded = passes_->prepared;
  passes_->next = (passes_->prepared + 1) % passes_->slots.size();
}

EngineFrameTimes EngineHybridMotionBlur::timings() const {
  return engineTimes(passes_->recordedSlot().recorder.readTimings());
}

uint32_t EngineHybridMotionBlur::maskPixels() const {
  return passes_->recordedSlot().hybrid.rayMask().counts().maskPixels;
}

uint32_t EngineHybridMotionBlur::shutterRayPixels() const {
  const passes::HybridStage& hybrid = passes_->recordedSlot().hybrid;
  return hybrid.tracesShutterRays() ? uint32_t(hybrid.shutterRays().counts().pixels) : 0u;
}

uint32_t EngineHybridMotionBlur::cutTraces() const { return passes_->recordedSlot().hybrid.cutTraces(); }

const FramePlan& EngineHybridMotionBlur::plan() const { return passes_->slots[passes_->prepared]->plan; }

uint32_t EngineHybridMotionBlur::framesInFlight() const { return uint32_t(passes_->slots.size()); }

}  // namespace hmb
