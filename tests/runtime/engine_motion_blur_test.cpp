// The engine backend: an engine's G-buffer, in its own buffers on its own device, blurred by
// commands recorded into its own command buffer, equals what the renderer's post-process method
// makes of its G-buffer.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/packing.hpp>
#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "hmblur/engine_motion_blur.h"
#include "hmblur/engine_scene.h"
#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "runtime/passes/hybrid_stage.h"
#include "tests/support/engine_device.h"
#include "tests/support/expect_error.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

constexpr uint32_t kWidth = 96, kHeight = 54;

// The renderer's G-buffer of a moving frame (the sharp method's layers) and its post-process
// frame with the settings it derived.
struct Frames {
  std::vector<glm::vec4> color;
  std::vector<float> depth;
  std::vector<glm::vec2> velocity;
  std::vector<glm::vec4> normal;
  std::vector<uint32_t> objectId;
  std::vector<glm::vec4> blurred;
  passes::PostProcessSettings settings;
  std::optional<passes::HybridSettings> hybrid;
  float frameTime = 0.0f;
};

// method: PostProcess or Hybrid, the frame `blurred` holds.
// frameTime: the scene's own when not given.
Frames renderedFrames(const scene::Scene& scene, Method method = Method::PostProcess,
                      std::optional<float> frameTime = std::nullopt) {
  Renderer renderer(VulkanTest::context());
  RenderSettings settings;
  settings.width = kWidth;
  settings.height = kHeight;
  settings.frameTime = frameTime;
  settings.method = Method::Sharp;
  const RenderResult sharp = renderer.render(scene, settings);
  settings.method = method;
  const RenderResult blurred = renderer.render(scene, settings);
  Frames f;
  f.settings = *blurred.postprocess;
  if (blurred.hybrid) f.hybrid = blurred.hybrid->settings;
  f.frameTime = blurred.frameTime;
  const auto& rgba = sharp.image.find("")->values;
  const auto& z = sharp.image.find("depth")->values;
  const auto& v = sharp.image.find("velocity")->values;
  const auto& n = sharp.image.find("normal")->values;
  const auto& out = blurred.image.find("")->values;
  f.objectId = sharp.image.find("objectId")->ids;
  for (uint32_t i = 0; i < kWidth * kHeight; ++i) {
    f.color.emplace_back(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2], rgba[4 * i + 3]);
    f.depth.push_back(z[i]);
    f.velocity.emplace_back(v[2 * i], v[2 * i + 1]);
    f.normal.emplace_back(n[3 * i], n[3 * i + 1], n[3 * i + 2], 0.0f);
    f.blurred.emplace_back(out[4 * i], out[4 * i + 1], out[4 * i + 2], out[4 * i + 3]);
  }
  return f;
}

Frames renderedFrames(const char* sceneName) { return renderedFrames(scene::loadScene(sceneName)); }

template <class T>
std::span<const std::byte> bytesOf(const std::vector<T>& values) {
  return std::as_bytes(std::span<const T>(values));
}

// Runs the backend on the engine's device over `depth` (in `convention`) and returns the output.
std::vector<glm::vec4> blurOnTheEngine(Engine& engine, const Frames& f, const std::vector<float>& depth,
                                       EngineDepth convention, EngineFrameTimes* timings = nullptr) {
  std::vector<glm::vec4> result(f.color.size());
  {
    vk::Context context(engine.adopted(), countingOptions());
    EngineMotionBlur blur(context, kWidth, kHeight, f.settings, convention);
    Engine::OwnBuffer color = engine.makeBuffer(f.color.size() * sizeof(glm::vec4), bytesOf(f.color));
    Engine::OwnBuffer z = engine.makeBuffer(depth.size() * sizeof(float), bytesOf(depth));
    Engine::OwnBuffer velocity = engine.makeBuffer(f.velocity.size() * sizeof(glm::vec2), bytesOf(f.velocity));
    Engine::OwnBuffer output = engine.makeBuffer(result.size() * sizeof(glm::vec4));
    const VkCommandBuffer commands = engine.beginCommands();
    const uint64_t waits = context.hostWaits(), readbacks = context.hostReadbacks();
    blur.record(commands, {color.buffer, z.buffer, velocity.buffer}, output.buffer);
    // Recording a frame neither waits on the device nor reads anything back.
    EXPECT_EQ(context.hostWaits(), waits);
    EXPECT_EQ(context.hostReadbacks(), readbacks);
    engine.submitAndWait(commands);
    const std::vector<std::byte> bytes = engine.read(output);
    std::memcpy(result.data(), bytes.data(), result.size() * sizeof(glm::vec4));
    if (timings) *timings = blur.timings();
    EXPECT_EQ(context.validationErrors(), 0u);
    for (Engine::OwnBuffer* b : {&color, &z, &velocity, &output}) engine.destroy(*b);
  }
  EXPECT_TRUE(engine.errors.empty()) << engine.errors.front();
  EXPECT_TRUE(engine.stillUsable());
  return result;
}

class EngineMotionBlurScenes : public ::testing::TestWithParam<const char*> {};

TEST_P(EngineMotionBlurScenes, BlursTheEnginesGBufferAsThePostProcessMethodBlursItsOwn) {
  const Frames f = renderedFrames(GetParam());
  size_t moving = 0;
  for (const glm::vec2 v : f.velocity) moving += glm::length(v) > 1.0f;
  ASSERT_GT(moving, 50u) << "the frame must move for the comparison to mean anything";
  Engine engine(/*enableFeatures=*/true);
  EngineFrameTimes timings;
  const std::vector<glm::vec4> out = blurOnTheEngine(engine, f, f.depth, {}, &timings);
  size_t differ = 0, blurredPixels = 0;
  for (size_t i = 0; i < out.size(); ++i) {
    differ += std::memcmp(&out[i], &f.blurred[i], sizeof(glm::vec4)) != 0;
    blurredPixels += glm::any(glm::notEqual(f.blurred[i], f.color[i]));
  }
  EXPECT_EQ(differ, 0u) << "of " << out.size() << " pixels";
  EXPECT_GT(blurredPixels, 50u);
  std::vector<std::string> names;
  for (const EnginePassTime& pass : timings.passes) names.push_back(pass.name);
  EXPECT_EQ(names, (std::vector<std::string>{"pack-engine-gbuffer", "tile-max", "neighbor-max", "clear-gather-blocks",
                                             "list-gather-blocks", "gather", "copy-still-blocks"}));
}

INSTANTIATE_TEST_SUITE_P(EngineMotionBlurTest, EngineMotionBlurScenes, ::testing::Values("living-room", "temple"));

// Depth as z/w (standard and reversed, finite and infinite far) reads back as the same
// camera-space depth, up to the rounding of the conversion.
TEST(EngineMotionBlurTest, ZOverWDepthBuffersBlurAsCameraSpaceDepth) {
  const Frames f = renderedFrames("temple");
  Engine engine(/*enableFeatures=*/false);
  const float nearPlane = 0.05f, farPlane = 500.0f;
  const auto convert = [&](EngineDepth::Convention convention, float far) {
    std::vector<float> zw;
    for (const float d : f.depth) {
      const double n = nearPlane, fa = far, dd = d;
      double value = 0.0;
      if (convention == EngineDepth::Convention::StandardZ) value = fa * (dd - n) / (dd * (fa - n));
      else value = std::isinf(fa) ? n / dd : n * (fa - dd) / (dd * (fa - n));
      zw.push_back(static_cast<float>(value));
    }
    return zw;
  };
  for (auto [convention, far] : {std::pair{EngineDepth::Convention::StandardZ, farPlane},
                                 std::pair{EngineDepth::Convention::ReversedZ, farPlane},
                                 std::pair{EngineDepth::Convention::ReversedZ, INFINITY}}) {
    SCOPED_TRACE(std::to_string(int(convention)) + " far " + std::to_string(far));
    const std::vector<glm::vec4> out = blurOnTheEngine(engine, f, convert(convention, far), {convention, nearPlane, far});
    size_t close = 0;
    for (size_t i = 0; i < out.size(); ++i)
      close += glm::all(glm::lessThanEqual(glm::abs(glm::vec3(out[i]) - glm::vec3(f.blurred[i])), glm::vec3(1e-4f)));
    EXPECT_GE(double(close) / double(out.size()), 0.999);
  }
}

// The hybrid on an engine's frame (its G-buffer with normals and object ids, its geometry as a
// scene) equals the renderer's hybrid frame, bit for bit; recording it neither waits nor reads
// anything back.
TEST(EngineMotionBlurTest, TheHybridOnTheEnginesFrameIsTheRenderersHybrid) {
  const scene::Scene scene = scene::loadScene("living-room");
  const Frames f = renderedFrames(scene, Method::HybridRays);
  ASSERT_TRUE(f.hybrid);
  Engine engine(/*enableFeatures=*/true);
  std::vector<glm::vec4> out(f.color.size());
  {
    vk::Context context(engine.adopted(), countingOptions());
    EngineHybridMotionBlur blur(context, kWidth, kHeight, scene, *f.hybrid);
    Engine::OwnBuffer color = engine.makeBuffer(f.color.size() * sizeof(glm::vec4), bytesOf(f.color));
    Engine::OwnBuffer z = engine.makeBuffer(f.depth.size() * sizeof(float), bytesOf(f.depth));
    Engine::OwnBuffer velocity = engine.makeBuffer(f.velocity.size() * sizeof(glm::vec2), bytesOf(f.velocity));
    Engine::OwnBuffer normal = engine.makeBuffer(f.normal.size() * sizeof(glm::vec4), bytesOf(f.normal));
    Engine::OwnBuffer ids = engine.makeBuffer(f.objectId.size() * sizeof(uint32_t), bytesOf(f.objectId));
    Engine::OwnBuffer output = engine.makeBuffer(out.size() * sizeof(glm::vec4));
    blur.prepare(f.frameTime);
    const VkCommandBuffer commands = engine.beginCommands();
    const uint64_t waits = context.hostWaits(), readbacks = context.hostReadbacks();
    blur.record(commands, {color.buffer, z.buffer, velocity.buffer, normal.buffer, ids.buffer}, output.buffer);
    EXPECT_EQ(context.hostWaits(), waits);
    EXPECT_EQ(context.hostReadbacks(), readbacks);
    engine.submitAndWait(commands);
    const std::vector<std::byte> bytes = engine.read(output);
    std::memcpy(out.data(), bytes.data(), out.size() * sizeof(glm::vec4));
    EXPECT_GT(blur.shutterRayPixels(), 20u);
    EXPECT_EQ(blur.maskPixels(), 0u);  // beside the shutter rays the mask is left out
    std::vector<std::string> names;
    for (const EnginePassTime& pass : blur.timings().passes) names.push_back(pass.name);
    EXPECT_NE(std::find(names.begin(), names.end(), "shutter-rays-trace"), names.end());
    EXPECT_EQ(context.validationErrors(), 0u);
    for (Engine::OwnBuffer* b : {&color, &z, &velocity, &normal, &ids, &output}) engine.destroy(*b);
    // Without normals and ids the hybrid has nothing to find edges and objects in.
    expectError([&] { blur.record(VK_NULL_HANDLE, {color.buffer, z.buffer, velocity.buffer}, output.buffer); },
                "normal and objectId");
  }
  EXPECT_TRUE(engine.errors.empty());
  size_t differ = 0;
  for (size_t i = 0; i < out.size(); ++i) differ += std::memcmp(&out[i], &f.blurred[i], sizeof(glm::vec4)) != 0;
  EXPECT_EQ(differ, 0u) << "of " << out.size() << " pixels";
}

// A G-buffer in the engine's own buffers (colour, depth, velocity, normal, object id) and an
// output buffer, last.
// The engine's view of a frame's times: each pass once, with its runs, adding up to the frame.
void expectEachPassOnceAddingUpToTheFrame(const EngineFrameTimes& times) {
  ASSERT_TRUE(times.available()) << times.unavailable;
  std::set<std::string> names;
  double sum = 0.0;
  for (const EnginePassTime& pass : times.passes) {
    EXPECT_TRUE(names.insert(pass.name).second) << pass.name << " is named twice";
    EXPECT_GE(pass.runs, 1u) << pass.name;
    EXPECT_TRUE(std::isfinite(pass.milliseconds) && pass.milliseconds >= 0.0) << pass.name;
    sum += pass.milliseconds;
  }
  EXPECT_NEAR(sum, times.frameMilliseconds, 1e-6 * (1.0 + times.frameMilliseconds));
}

std::vector<Engine::OwnBuffer> engineBuffers(Engine& engine, const Frames& f) {
  return {engine.makeBuffer(f.color.size() * sizeof(glm::vec4), bytesOf(f.color)),
          engine.makeBuffer(f.depth.size() * sizeof(float), bytesOf(f.depth)),
          engine.makeBuffer(f.velocity.size() * sizeof(glm::vec2), bytesOf(f.velocity)),
          engine.makeBuffer(f.normal.size() * sizeof(glm::vec4), bytesOf(f.normal)),
          engine.makeBuffer(f.objectId.size() * sizeof(uint32_t), bytesOf(f.objectId)),
          engine.makeBuffer(f.color.size() * sizeof(glm::vec4))};
}

EngineGBuffer gbufferOf(const std::vector<Engine::OwnBuffer>& b) {
  return {b[0].buffer, b[1].buffer, b[2].buffer, b[3].buffer, b[4].buffer};
}

// The engine's output equals the renderer's blurred frame, bit for bit.
void expectTheRenderersFrame(const Engine& engine, const Engine::OwnBuffer& output, const Frames& f) {
  std::vector<glm::vec4> out(f.color.size());
  const std::vector<std::byte> bytes = engine.read(output);
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(glm::vec4));
  size_t differ = 0;
  for (size_t i = 0; i < out.size(); ++i) differ += std::memcmp(&out[i], &f.blurred[i], sizeof(glm::vec4)) != 0;
  EXPECT_EQ(differ, 0u) << "of " << out.size() << " pixels";
}

// The frames after the first, where instances moved, on a device whose memory the host cannot
// map (a discrete GPU's; staged writes would wait there): prepare() and record() neither wait
// nor read back, the instances' tree is built inside the engine's command buffer, and the
// frame is still the renderer's, bit for bit.
TEST(EngineMotionBlurTest, AFrameWhoseInstancesMovedNeitherWaitsNorReadsBack) {
  const scene::Scene scene = scene::loadScene("living-room");
  const Frames first = renderedFrames(scene, Method::HybridRays);
  const Frames later = renderedFrames(scene, Method::HybridRays, first.frameTime + 2.0f / scene.settings.fps);
  ASSERT_TRUE(first.hybrid && later.hybrid);
  ASSERT_NE(first.blurred, later.blurred);
  Engine engine(/*enableFeatures=*/true);
  vk::ContextOptions options = countingOptions();
  options.hostVisibleDeviceLocalBytes = 256ull << 20;
  vk::Context context(engine.adopted(), options);
  EngineHybridMotionBlur blur(context, kWidth, kHeight, scene, *later.hybrid);
  std::vector<Engine::OwnBuffer> owned;
  const auto frameOnTheEngine = [&](const Frames& f) {
    for (Engine::OwnBuffer& b : owned) engine.destroy(b);
    owned = engineBuffers(engine, f);
    const VkCommandBuffer commands = engine.beginCommands();
    blur.record(commands, gbufferOf(owned), owned.back().buffer);
    return commands;
  };
  blur.prepare(first.frameTime);  // the meshes' trees: built once, and waited for
  engine.submitAndWait(frameOnTheEngine(first));

  const uint64_t waits = context.hostWaits(), readbacks = context.hostReadbacks();
  blur.prepare(later.frameTime);
  EXPECT_FALSE(blur.plan().runs("hybrid-bvh-meshes"));
  EXPECT_TRUE(blur.plan().runs("hybrid-bvh-instances"));
  const VkCommandBuffer commands = frameOnTheEngine(later);
  EXPECT_EQ(context.hostWaits(), waits);
  EXPECT_EQ(context.hostReadbacks(), readbacks);
  engine.submitAndWait(commands);
  expectTheRenderersFrame(engine, owned.back(), later);
  EXPECT_GT(blur.shutterRayPixels(), 20u);
  EXPECT_EQ(blur.cutTraces(), 0u);  // the living room's rays are short
  const EngineFrameTimes times = blur.timings();
  expectEachPassOnceAddingUpToTheFrame(times);
  const auto topLevel = std::find_if(times.passes.begin(), times.passes.end(),
                                     [](const EnginePassTime& p) { return p.name == "hybrid-bvh-instances"; });
  ASSERT_NE(topLevel, times.passes.end());
  EXPECT_GT(topLevel->runs, 1u);  // the instances' tree is built in several passes of one name
  EXPECT_EQ(context.validationErrors(), 0u);
  for (Engine::OwnBuffer& b : owned) engine.destroy(b);
  EXPECT_TRUE(engine.errors.empty());
}

// A skinned mesh on the engine's frame, on a device whose memory the host cannot map (staged
// writes would wait there): the first prepare() builds the trees and prepares the refit (setup,
// which may wait: the header says so); from then on neither prepare() nor record() waits or
// reads back, frame after frame, though the mesh deforms and its tree is refitted in each (the
// joints travel in the command buffer); every frame is the renderer's hybrid frame, bit for bit.
TEST(EngineMotionBlurTest, ADeformingFrameAfterTheFirstNeitherWaitsNorReadsBack) {
  const scene::Scene scene =
      scene::loadScene((std::filesystem::path(HMB_DEFORMING_SCENES_DIR) / "skinned-arm.gltf").string());
  const Frames first = renderedFrames(scene, Method::HybridRays);
  const Frames later = renderedFrames(scene, Method::HybridRays, first.frameTime - 3.0f / scene.settings.fps);
  const Frames last = renderedFrames(scene, Method::HybridRays, first.frameTime - 1.0f / scene.settings.fps);
  ASSERT_TRUE(first.hybrid && later.hybrid && last.hybrid);
  ASSERT_NE(first.blurred, later.blurred);
  Engine engine(/*enableFeatures=*/true);
  vk::ContextOptions options = countingOptions();
  options.hostVisibleDeviceLocalBytes = 256ull << 20;
  vk::Context context(engine.adopted(), options);
  EngineHybridMotionBlur blur(context, kWidth, kHeight, scene, *first.hybrid);
  blur.prepare(first.frameTime);  // setup: the trees, the refit's first round trip
  for (const Frames* f : {&first, &later, &last}) {
    SCOPED_TRACE(f->frameTime);
    std::vector<Engine::OwnBuffer> owned = engineBuffers(engine, *f);
    const uint64_t waits = context.hostWaits(), readbacks = context.hostReadbacks();
    if (f != &first) blur.prepare(f->frameTime);
    EXPECT_TRUE(blur.plan().runs("bvh-refit"));
    EXPECT_EQ(blur.plan().runs("hybrid-bvh-meshes"), f == &first);
    const VkCommandBuffer commands = engine.beginCommands();
    blur.record(commands, gbufferOf(owned), owned.back().buffer);
    EXPECT_EQ(context.hostWaits(), waits);
    EXPECT_EQ(context.hostReadbacks(), readbacks);
    engine.submitAndWait(commands);
    expectTheRenderersFrame(engine, owned.back(), *f);
    const EngineFrameTimes times = blur.timings();
    for (const char* pass : {"deform-vertices", "bvh-deformed-leaves", "bvh-refit", "hybrid-bvh-instances"})
      EXPECT_TRUE(std::any_of(times.passes.begin(), times.passes.end(),
                              [&](const EnginePassTime& p) { return p.name == pass; }))
          << pass << " is not in the recorded frame";
    for (Engine::OwnBuffer& b : owned) engine.destroy(b);
  }
  EXPECT_EQ(context.validationErrors(), 0u);
  EXPECT_TRUE(engine.errors.empty());
}

// An engine that keeps matrices: the living room given as an EngineScene (its meshes once, the
// frame's world transforms now and one frame earlier) traces as the scene it came from; the
// transforms go through translation, rotation and scale, so to rounding.
TEST(EngineMotionBlurTest, AnEngineSceneOfMatricesTracesAsTheSceneItCameFrom) {
  const scene::Scene original = scene::loadScene("living-room");
  const Frames f = renderedFrames(original, Method::HybridRays);
  const float t = f.frameTime, before = t - 1.0f / original.settings.fps;
  EngineScene engineScene(original.settings.fps, original.settings.exposure, original.settings.softZExtent);
  for (const scene::Mesh& mesh : original.meshes) {
    const scene::Material& m = original.materials[mesh.material];
    engineScene.addMesh(mesh.positions, mesh.normals, mesh.indices, glm::vec3(m.baseColorFactor), m.doubleSided);
  }
  engineScene.setLight(original.light);
  std::vector<EngineScene::Instance> instances;
  for (const scene::Instance& in : original.instances)
    instances.push_back({in.mesh, in.objectId, original.worldMatrixAt(in.node, t), original.worldMatrixAt(in.node, before)});
  ASSERT_TRUE(original.camera && original.camera->node >= 0);
  const auto cameraNode = static_cast<uint32_t>(original.camera->node);
  engineScene.setFrame(t, instances,
                       {original.worldMatrixAt(cameraNode, t), original.worldMatrixAt(cameraNode, before),
                        original.camera->yfov, original.camera->znear, original.camera->zfar});

  vk::Context& context = VulkanTest::context();
  const vk::Buffer color = vk::uploadedBuffer(context, f.color, "colour");
  const vk::Buffer z = vk::uploadedBuffer(context, f.depth, "depth");
  const vk::Buffer velocity = vk::uploadedBuffer(context, f.velocity, "velocity");
  const vk::Buffer normal = vk::uploadedBuffer(context, f.normal, "normal");
  const vk::Buffer ids = vk::uploadedBuffer(context, f.objectId, "ids");
  const vk::Buffer output(context, f.color.size() * sizeof(glm::vec4), vk::MemoryUse::Readback, "output");
  EngineHybridMotionBlur blur(context, kWidth, kHeight, engineScene.scene(), *f.hybrid);
  const auto recordFrame = [&] {
    context.submitAndWait([&](VkCommandBuffer commands) {
      blur.record(commands, {color.handle(), z.handle(), velocity.handle(), normal.handle(), ids.handle()},
                  output.handle());
    });
  };
  const auto expectRendererFrame = [&] {
    const std::vector<glm::vec4> out = output.download<glm::vec4>();
    size_t close = 0, exact = 0;
    for (size_t i = 0; i < out.size(); ++i) {
      exact += out[i] == f.blurred[i];
      close += glm::all(glm::lessThanEqual(glm::abs(out[i] - f.blurred[i]), glm::vec4(1e-3f)));
    }
    EXPECT_GE(double(close) / double(out.size()), 0.999) << exact << " exact of " << out.size();
  };
  blur.prepare(t);
  EXPECT_TRUE(blur.plan().runs("hybrid-bvh-meshes"));
  EXPECT_TRUE(blur.plan().runs("hybrid-bvh-instances"));
  // Prepared again before the frame was recorded: the instances' tree is still to be built.
  blur.prepare(t);
  EXPECT_FALSE(blur.plan().runs("hybrid-bvh-meshes"));
  EXPECT_TRUE(blur.plan().runs("hybrid-bvh-instances"));
  recordFrame();
  expectRendererFrame();
  EXPECT_GT(blur.shutterRayPixels(), 20u);
  // The same frame again: the library keeps both trees and says so in the plan.
  blur.prepare(t);
  EXPECT_FALSE(blur.plan().runs("hybrid-bvh-meshes"));
  EXPECT_FALSE(blur.plan().runs("hybrid-bvh-instances"));
  EXPECT_TRUE(blur.plan().runs("shutter-rays-trace"));
  recordFrame();
  expectRendererFrame();

  // What an engine can get wrong is one line naming it.
  expectError([&] { engineScene.setFrame(t, std::vector<EngineScene::Instance>{{99, 1}}, {}); }, "instance 0");
  glm::mat4 shear(1.0f);
  shear[1][0] = 0.5f;
  expectError([&] { engineScene.setFrame(t, std::vector<EngineScene::Instance>{{0, 1, shear, shear}}, {}); }, "shear");
  expectError([&] { engineScene.setFrame(t, std::vector<EngineScene::Instance>{{0, 0}}, {}); }, "object id 0");
}

// The G-buffer as the engine's images. The host's reference of what the images path decodes
// (kernels/engine/engine_pixel.glsl): octahedral normals, NDC velocities; and the encodings.
glm::vec2 octahedralEncode(glm::vec3 n) {
  n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  glm::vec2 e(n.x, n.y);
  if (n.z < 0.0f)
    e = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
  return e;
}
glm::vec3 octahedralDecode(glm::vec2 e) {
  glm::vec3 n(e, 1.0f - std::abs(e.x) - std::abs(e.y));
  const float fold = std::max(-n.z, 0.0f);
  n.x += n.x >= 0.0f ? -fold : fold;
  n.y += n.y >= 0.0f ? -fold : fold;
  return glm::normalize(n);
}
int16_t snorm16(float x) { return int16_t(std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f)); }
float fromSnorm16(int16_t c) { return std::max(float(c) / 32767.0f, -1.0f); }

// The frame's G-buffer in images of the given formats, its depth as standard z/w over
// [near, far], and what the buffers path must be given to blur the same values.
struct ImageFrame {
  std::vector<Engine::OwnImage> images;  // colour, depth, velocity, normal, object id, output
  EngineGBufferImages gbuffer;
  EngineImage output;
  Frames decoded;                 // the values the images hold, as the buffers path takes them
  std::vector<float> depthValues;  // standard z/w
};
constexpr float kNear = 0.05f, kFar = 200.0f;

// Which formats the G-buffer's images take: 32-bit ones; RGBA16F colour, RG16F velocity in NDC
// and octahedral RG16 SNORM normals; or B10G11R11 colour, RG16F velocity in pixels and
// A2B10G10R10 UNORM normals (xyz biased).
enum class ImageFormats { Full, Engine, Packed };

ImageFrame imageFrame(Engine& engine, const Frames& f, ImageFormats formats) {
  const bool engineFormats = formats != ImageFormats::Full;
  ImageFrame r;
  r.decoded = f;
  const size_t n = f.color.size();
  constexpr VkImageUsageFlags kSampled = VK_IMAGE_USAGE_SAMPLED_BIT;
  constexpr VkImageLayout kRead = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  // Colour: RGBA32F, RGBA16F or B10G11R11.
  if (formats == ImageFormats::Packed) {
    std::vector<uint32_t> packed(n);
    for (size_t i = 0; i < n; ++i) {
      packed[i] = glm::packF2x11_1x10(glm::max(glm::vec3(f.color[i]), glm::vec3(0.0f)));
      r.decoded.color[i] = glm::vec4(glm::unpackF2x11_1x10(packed[i]), f.color[i].a);
    }
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_B10G11R11_UFLOAT_PACK32, 4, kSampled,
                                        bytesOf(packed), kRead));
  } else {
    std::vector<uint16_t> halfColor(4 * n);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 4; ++c) {
        halfColor[4 * i + c] = glm::packHalf1x16(f.color[i][c]);
        if (engineFormats) r.decoded.color[i][c] = glm::unpackHalf1x16(halfColor[4 * i + c]);
      }
    r.images.push_back(engineFormats ? engine.makeImage(kWidth, kHeight, VK_FORMAT_R16G16B16A16_SFLOAT, 8, kSampled,
                                                        bytesOf(halfColor), kRead)
                                     : engine.makeImage(kWidth, kHeight, VK_FORMAT_R32G32B32A32_SFLOAT, 16, kSampled,
                                                        bytesOf(f.color), kRead));
  }
  // Depth: D32 holding standard z/w (the far plane where the renderer's is background).
  r.depthValues.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const float d = f.depth[i];
    r.depthValues[i] = d >= kFar ? 1.0f : kFar * (d - kNear) / (d * (kFar - kNear));
  }
  r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_D32_SFLOAT, 4,
                                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                      bytesOf(r.depthValues), VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL));
  // Velocity: RG16F in NDC or in pixels, or RG32F in pixels.
  if (formats == ImageFormats::Packed) {
    std::vector<uint16_t> pixels(2 * n);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 2; ++c) {
        pixels[2 * i + c] = glm::packHalf1x16(f.velocity[i][c]);
        r.decoded.velocity[i][c] = glm::unpackHalf1x16(pixels[2 * i + c]);
      }
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_R16G16_SFLOAT, 4, kSampled, bytesOf(pixels), kRead));
  } else if (engineFormats) {
    std::vector<uint16_t> ndc(2 * n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec2 size(kWidth, kHeight);
      for (int c = 0; c < 2; ++c) {
        ndc[2 * i + c] = glm::packHalf1x16(f.velocity[i][c] / (0.5f * size[c]));
        r.decoded.velocity[i][c] = glm::unpackHalf1x16(ndc[2 * i + c]) * 0.5f * size[c];
      }
    }
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_R16G16_SFLOAT, 4, kSampled, bytesOf(ndc), kRead));
  } else {
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_R32G32_SFLOAT, 8, kSampled, bytesOf(f.velocity), kRead));
  }
  // Normal: xyz biased in A2B10G10R10 UNORM, octahedral RG16 SNORM, or xyz in RGBA32F.
  if (formats == ImageFormats::Packed) {
    std::vector<uint32_t> packed(n);
    for (size_t i = 0; i < n; ++i) {
      packed[i] = glm::packUnorm3x10_1x2(glm::vec4(glm::vec3(f.normal[i]) * 0.5f + 0.5f, 1.0f));
      for (int c = 0; c < 3; ++c)
        r.decoded.normal[i][c] = float((packed[i] >> (10 * c)) & 1023u) / 1023.0f * 2.0f - 1.0f;
    }
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4, kSampled,
                                        bytesOf(packed), kRead));
  } else if (engineFormats) {
    std::vector<int16_t> octahedral(2 * n);
    for (size_t i = 0; i < n; ++i) {
      const glm::vec3 normal(f.normal[i]);
      const glm::vec2 e = glm::length(normal) > 0.0f ? octahedralEncode(normal) : glm::vec2(0.0f);
      octahedral[2 * i] = snorm16(e.x);
      octahedral[2 * i + 1] = snorm16(e.y);
      r.decoded.normal[i] =
          glm::vec4(octahedralDecode({fromSnorm16(octahedral[2 * i]), fromSnorm16(octahedral[2 * i + 1])}), 0.0f);
    }
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_R16G16_SNORM, 4, kSampled, bytesOf(octahedral), kRead));
  } else {
    r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_R32G32B32A32_SFLOAT, 16, kSampled, bytesOf(f.normal), kRead));
  }
  r.images.push_back(engine.makeImage(kWidth, kHeight, VK_FORMAT_R32_UINT, 4, kSampled, bytesOf(f.objectId), kRead));
  const VkFormat outputFormat = engineFormats ? VK_FORMAT_R16G16B16A16_SFLOAT : VK_FORMAT_R32G32B32A32_SFLOAT;
  r.images.push_back(engine.makeImage(kWidth, kHeight, outputFormat, engineFormats ? 8 : 16, VK_IMAGE_USAGE_STORAGE_BIT,
                                      {}, VK_IMAGE_LAYOUT_GENERAL));
  const auto view = [&](size_t k, VkImageLayout layout) { return EngineImage{r.images[k].view, r.images[k].format, layout}; };
  r.gbuffer.color = view(0, kRead);
  r.gbuffer.depth = view(1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
  r.gbuffer.velocity = view(2, kRead);
  r.gbuffer.normal = view(3, kRead);
  r.gbuffer.objectId = view(4, kRead);
  r.output = view(5, VK_IMAGE_LAYOUT_GENERAL);
  if (formats == ImageFormats::Engine) {
    r.gbuffer.velocityUnits = EngineGBufferImages::VelocityUnits::Ndc;
    r.gbuffer.normalEncoding = EngineGBufferImages::NormalEncoding::Octahedral;
  } else if (formats == ImageFormats::Packed) {
    r.gbuffer.normalEncoding = EngineGBufferImages::NormalEncoding::XyzUnorm;
  }
  return r;
}

// The output image's pixels as linear RGBA floats.
std::vector<glm::vec4> outputPixels(Engine& engine, const ImageFrame& frame) {
  const Engine::OwnImage& image = frame.images.back();
  const std::vector<std::byte> bytes = engine.read(image, VK_IMAGE_LAYOUT_GENERAL);
  std::vector<glm::vec4> pixels(size_t(image.width) * image.height);
  for (size_t i = 0; i < pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) {
      if (image.format == VK_FORMAT_R16G16B16A16_SFLOAT) {
        uint16_t h;
        std::memcpy(&h, bytes.data() + 8 * i + 2 * c, 2);
        pixels[i][c] = glm::unpackHalf1x16(h);
      } else {
        std::memcpy(&pixels[i][c], bytes.data() + 16 * i + 4 * c, 4);
      }
    }
  return pixels;
}

// Pixels of `images` (an image output) that are not `buffers` (the buffers path's output,
// given the values the images hold): exactly, or within the half-float output's rounding.
size_t differingPixels(const std::vector<glm::vec4>& images, const std::vector<glm::vec4>& buffers, bool halfOutput) {
  size_t differ = 0;
  for (size_t i = 0; i < images.size(); ++i) {
    bool same = images[i].a == 1.0f;
    for (int c = 0; c < 3; ++c) {
      const float a = images[i][c], b = buffers[i][c];
      same = same && std::isfinite(a) && (halfOutput ? std::abs(a - b) <= std::abs(b) * 0x1p-10f + 0x1p-24f : a == b);
    }
    differ += !same;
  }
  return differ;
}

// The engine's own images, read in place: in full-precision formats the images path blurs as
// the buffers path does, bit for bit; in the formats engines draw (RGBA16F or B10G11R11 colour,
// RGBA16F output, D32 depth as z/w, RG16F velocity in NDC or pixels, octahedral RG16 SNORM or
// biased A2B10G10R10 normals, R32UI ids) it blurs the values they hold (the host's decoding,
// given to the buffers path) to the output's rounding; post-process and hybrid alike, under
// validation, recording without a wait.
TEST(EngineMotionBlurTest, TheEnginesImagesBlurAsTheValuesTheyHold) {
  const scene::Scene scene = scene::loadScene("living-room");
  const Frames f = renderedFrames(scene, Method::Hybrid);
  ASSERT_TRUE(f.hybrid);
  const EngineDepth depth{EngineDepth::Convention::StandardZ, kNear, kFar};
  for (const ImageFormats formats : {ImageFormats::Full, ImageFormats::Engine, ImageFormats::Packed}) {
    const bool engineFormats = formats != ImageFormats::Full;
    SCOPED_TRACE(formats == ImageFormats::Full ? "full precision" : formats == ImageFormats::Engine ? "RGBA16F, NDC, octahedral" : "B10G11R11, A2B10G10R10");
    Engine engine(/*enableFeatures=*/true);
    {
      vk::Context context(engine.adopted(), countingOptions());
      ImageFrame frame = imageFrame(engine, f, formats);
      std::vector<Engine::OwnBuffer> buffers = engineBuffers(engine, frame.decoded);
      engine.destroy(buffers[1]);
      buffers[1] = engine.makeBuffer(frame.depthValues.size() * sizeof(float), bytesOf(frame.depthValues));
      const auto bufferOutput = [&] {
        const std::vector<std::byte> bytes = engine.read(buffers.back());
        std::vector<glm::vec4> out(f.color.size());
        std::memcpy(out.data(), bytes.data(), out.size() * sizeof(glm::vec4));
        return out;
      };
      // Post-process, without and with the surfaces' images.
      EngineMotionBlur blur(context, kWidth, kHeight, f.settings, depth);
      for (const bool surfaces : {false, true}) {
        EngineGBufferImages gbuffer = frame.gbuffer;
        if (!surfaces) gbuffer.normal = gbuffer.objectId = {};
        VkCommandBuffer commands = engine.beginCommands();
        const uint64_t waits = context.hostWaits(), readbacks = context.hostReadbacks();
        blur.record(commands, gbuffer, frame.output);
        EXPECT_EQ(context.hostWaits(), waits);
        EXPECT_EQ(context.hostReadbacks(), readbacks);
        engine.submitAndWait(commands);
        const std::vector<glm::vec4> fromImages = outputPixels(engine, frame);
        commands = engine.beginCommands();
        EngineGBuffer g = gbufferOf(buffers);
        if (!surfaces) g.normal = g.objectId = VK_NULL_HANDLE;
        blur.record(commands, g, buffers.back().buffer);
        engine.submitAndWait(commands);
        EXPECT_EQ(differingPixels(fromImages, bufferOutput(), engineFormats), 0u) << "post-process, surfaces " << surfaces;
      }
      // The hybrid.
      EngineHybridMotionBlur hybrid(context, kWidth, kHeight, scene, *f.hybrid, depth);
      hybrid.prepare(f.frameTime);
      VkCommandBuffer commands = engine.beginCommands();
      hybrid.record(commands, frame.gbuffer, frame.output);
      engine.submitAndWait(commands);
      EXPECT_GT(hybrid.maskPixels(), 20u);
      const std::vector<glm::vec4> fromImages = outputPixels(engine, frame);
      commands = engine.beginCommands();
      hybrid.record(commands, gbufferOf(buffers), buffers.back().buffer);
      engine.submitAndWait(commands);
      EXPECT_EQ(differingPixels(fromImages, bufferOutput(), engineFormats), 0u) << "hybrid";
      // Wrong images are one line each.
      EngineGBufferImages wrong = frame.gbuffer;
      wrong.objectId = wrong.color;
      expectError([&] { hybrid.record(VK_NULL_HANDLE, wrong, frame.output); }, "'objectId'");
      wrong = frame.gbuffer;
      wrong.depth.format = VK_FORMAT_R32_UINT;
      expectError([&] { blur.record(VK_NULL_HANDLE, wrong, frame.output); }, "a depth format");
      EngineImage output = frame.output;
      output.format = VK_FORMAT_R8G8B8A8_UNORM;
      expectError([&] { blur.record(VK_NULL_HANDLE, frame.gbuffer, output); }, "R16G16B16A16_SFLOAT");
      output = frame.output;
      output.layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
      expectError([&] { blur.record(VK_NULL_HANDLE, frame.gbuffer, output); }, "GENERAL");
      EXPECT_EQ(context.validationErrors(), 0u);
      for (Engine::OwnImage& image : frame.images) engine.destroy(image);
      for (Engine::OwnBuffer& b : buffers) engine.destroy(b);
    }
    EXPECT_TRUE(engine.errors.empty()) << engine.errors.front();
  }
}

// The engine's settings are the renderer's for the scene at the engine's image size, under the
// engine API's own names; an empty image is a one-line error.
// Frames in flight: three sets of per-frame buffers over one set of mesh trees. Four frames of
// the living room whose instances move, recorded one after another into their own command
// buffers and submitted together, each the renderer's frame bit for bit; only the first builds
// the meshes' trees (the others plan them shared, the fourth takes the first set again).
TEST(EngineMotionBlurTest, FramesInFlightShareTheMeshTrees) {
  const scene::Scene scene = scene::loadScene("living-room");
  std::vector<Frames> frames;
  for (int f = 0; f < 4; ++f)
    frames.push_back(renderedFrames(scene, Method::Hybrid, scene.settings.frameTime - float(f) / scene.settings.fps));
  ASSERT_NE(frames[0].blurred, frames[1].blurred);
  Engine engine(/*enableFeatures=*/true);
  vk::Context context(engine.adopted(), countingOptions());
  for (const uint32_t inFlight : {1u, 3u}) {
    SCOPED_TRACE(inFlight);
    EngineHybridMotionBlur blur(context, kWidth, kHeight, scene, *frames[0].hybrid, {}, nullptr, inFlight);
    EXPECT_EQ(blur.framesInFlight(), inFlight);
    std::vector<std::vector<Engine::OwnBuffer>> owned;
    // Records frames [first, last) one after another, then submits them all and checks each.
    const auto inFlightTogether = [&](size_t first, size_t last) {
      std::vector<VkCommandBuffer> commands;
      for (size_t f = first; f < last; ++f) {
        owned.push_back(engineBuffers(engine, frames[f]));
        blur.prepare(frames[f].frameTime);
        const auto meshes = std::find_if(blur.plan().passes().begin(), blur.plan().passes().end(),
                                         [](const PlannedPass& p) { return p.name == "hybrid-bvh-meshes"; });
        ASSERT_NE(meshes, blur.plan().passes().end());
        EXPECT_EQ(meshes->run, f == 0) << f;
        if (f > 0) EXPECT_EQ(meshes->reason, passes::kSharedMeshTreesReason) << f;
        commands.push_back(engine.beginCommands());
        blur.record(commands.back(), gbufferOf(owned.back()), owned.back().back().buffer);
      }
      for (size_t k = 0; k < commands.size(); ++k) {
        engine.submitAndWait(commands[k]);
        expectTheRenderersFrame(engine, owned[first + k].back(), frames[first + k]);
      }
    };
    inFlightTogether(0, inFlight);
    if (inFlight == 3) inFlightTogether(3, 4);  // the first set again
    for (auto& buffers : owned)
      for (Engine::OwnBuffer& b : buffers) engine.destroy(b);
  }
  EXPECT_EQ(context.validationErrors(), 0u);
  EXPECT_TRUE(engine.errors.empty());
}

// Three frames in flight hold the trees and the scene once: over a dense mesh (a 200 x 200 grid
// of quads, two instances of it moving) the first frame's prepare() takes the memory of the
// trees and the scene's vertices, triangles and materials; the second's and third's (the other
// sets) less by more than a copy of the trees, and a small part of the first's: their frame
// inputs and top levels alone.
TEST(EngineMotionBlurTest, FramesInFlightHoldTheTreesOnce) {
  constexpr uint32_t kCells = 200;
  std::vector<glm::vec3> positions, normals;
  std::vector<uint32_t> indices;
  for (uint32_t y = 0; y <= kCells; ++y)
    for (uint32_t x = 0; x <= kCells; ++x) {
      const float u = float(x) / kCells, v = float(y) / kCells;
      positions.emplace_back(u - 0.5f, v - 0.5f, 0.05f * std::sin(20.0f * u) * std::cos(20.0f * v));
      normals.emplace_back(0.0f, 0.0f, 1.0f);
    }
  for (uint32_t y = 0; y < kCells; ++y)
    for (uint32_t x = 0; x < kCells; ++x) {
      const uint32_t a = y * (kCells + 1) + x, b = a + 1, c = a + kCells + 1, d = c + 1;
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
  EngineScene engineScene(60.0f, 0.5f / 60.0f, 0.05f);
  engineScene.addMesh(positions, normals, indices);
  EngineScene::Camera camera;
  camera.worldNow = camera.worldPrevious = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 3.0f));
  const auto frameAt = [&](int f) {
    const auto at = [](float x) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, 0.0f)); };
    const std::vector<EngineScene::Instance> instances = {{0, 1, at(-0.5f + 0.02f * f), at(-0.5f + 0.02f * (f - 1))},
                                                          {0, 2, at(0.5f - 0.02f * f), at(0.5f - 0.02f * (f - 1))}};
    engineScene.setFrame(float(f) / 60.0f, instances, camera);
  };
  frameAt(0);
  const Frames f = renderedFrames(engineScene.scene(), Method::Hybrid);
  ASSERT_TRUE(f.hybrid);
  Engine engine(/*enableFeatures=*/true);
  vk::Context context(engine.adopted(), countingOptions());
  std::vector<Engine::OwnBuffer> buffers = engineBuffers(engine, f);
  std::vector<double> added;  // by each frame's prepare() and record()
  {
    EngineHybridMotionBlur blur(context, kWidth, kHeight, engineScene.scene(), *f.hybrid, {}, nullptr, 3);
    for (int k = 0; k < 3; ++k) {
      const uint64_t before = context.memoryInUse();
      frameAt(k);
      blur.prepare(float(k) / 60.0f);
      const VkCommandBuffer commands = engine.beginCommands();
      blur.record(commands, gbufferOf(buffers), buffers.back().buffer);
      engine.submitAndWait(commands);
      added.push_back(double(context.memoryInUse()) - double(before));
    }
  }
  for (Engine::OwnBuffer& b : buffers) engine.destroy(b);
  // One copy of the trees, as the renderer builds them for the same scene.
  RenderSettings render;
  render.width = kWidth;
  render.height = kHeight;
  render.method = Method::Hybrid;
  Renderer renderer(VulkanTest::context());
  const RenderResult result = renderer.render(engineScene.scene(), render);
  ASSERT_TRUE(result.memory.bvhAllocatedBytesPerTriangle.has_value());
  // The nodes and indices, as the renderer reports them, and the leaves' triangles (3 vec4 each).
  const double treeBytes = (*result.memory.bvhAllocatedBytesPerTriangle + 48.0) * double(indices.size() / 3);
  std::cout << "[ in flight ] bytes taken by frames 1, 2, 3: " << added[0] << ", " << added[1] << ", " << added[2]
            << "; one copy of the trees " << treeBytes << "\n";
  for (int k = 1; k < 3; ++k) {
    EXPECT_LT(added[k], added[0] - 0.9 * treeBytes) << k;
    EXPECT_LT(added[k], 0.1 * added[0]) << k;
  }
  EXPECT_EQ(context.validationErrors(), 0u);
  EXPECT_TRUE(engine.errors.empty());
}

TEST(EngineMotionBlurTest, TheEnginesSettingsAreTheRenderersForItsScene) {
  const scene::Scene scene = scene::loadScene("temple");
  RenderSettings render;
  render.width = 640;
  render.height = 360;
  render.method = Method::PostProcess;
  EXPECT_TRUE(engineBlurSettingsFor(scene, 640, 360) == postProcessSettingsFor(scene, render));
  EXPECT_FALSE(engineBlurSettingsFor(scene, 640, 360) == engineBlurSettingsFor(scene, 1280, 720));  // the tiles
  render.method = Method::Hybrid;
  const EngineHybridSettings paper = engineHybridSettingsFor(scene, 640, 360);
  EXPECT_TRUE(paper.blur == hybridSettingsFor(scene, render).blur);
  EXPECT_EQ(paper.shutterRays, hybridSettingsFor(scene, render).shutterRays);
  render.method = Method::HybridRays;
  EXPECT_EQ(engineHybridSettingsFor(scene, 640, 360, true).shutterRays, hybridSettingsFor(scene, render).shutterRays);
  EXPECT_NE(engineHybridSettingsFor(scene, 640, 360, true).shutterRays, paper.shutterRays);
  expectError([&] { engineBlurSettingsFor(scene, 0, 360); }, "an empty image");
}

TEST(EngineMotionBlurTest, DepthConventionsWithoutTheirPlanesAreOneLineErrors) {
  const passes::PostProcessSettings settings;
  const vk::Context& context = VulkanTest::context();
  using C = EngineDepth::Convention;
  expectError([&] { EngineMotionBlur(context, 8, 8, settings, {C::ReversedZ, 0.0f, 10.0f}); },
                        "near plane");
  expectError([&] { EngineMotionBlur(context, 8, 8, settings, {C::StandardZ, 0.1f, INFINITY}); },
                        "finite far plane");
  expectError([&] { EngineMotionBlur(context, 8, 8, settings, {C::StandardZ, 1.0f, 0.5f}); },
                        "beyond the near plane");
  expectError([&] { EngineMotionBlur(context, 0, 8, settings); }, "empty image");
  passes::PostProcessSettings curved;
  curved.motionPath = passes::MotionPath::Curved;
  expectError([&] { EngineMotionBlur(context, 8, 8, curved); }, "straight velocities only");
}

}  // namespace
}  // namespace hmb::test
