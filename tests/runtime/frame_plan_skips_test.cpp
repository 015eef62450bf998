// The frame plan leaves out the passes that cannot change the frame, and says why. Each skip
// is checked against the same frame with every pass run: the images must be identical.
#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <numbers>

#include <glm/gtc/quaternion.hpp>

#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "runtime/device_scene/deformed_vertices.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/hybrid_stage.h"
#include "runtime/passes/shutter_path_pass.h"
#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/scene_builder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using FramePlanSkipsTest = VulkanTest;

// The living room's vase slides over [0, 0.4] s; at 0.45 s (previous frame 0.4417 s) nothing moves.
constexpr float kMovingTime = 0.2f;
constexpr float kStillTime = 0.45f;

RenderResult renderAt(Renderer& renderer, const scene::Scene& scene, const std::string& method, float time,
                      bool skip, passes::MotionPath path = passes::MotionPath::Linear) {
  RenderSettings settings;
  settings.postprocess.motionPath = path;
  settings.method = parseMethod(method);
  settings.width = 64;
  settings.height = 36;
  settings.frameTime = time;
  settings.skipUnneededPasses = skip;
  settings.reference.samplesPerPixel = 8;
  return renderer.render(scene, settings);
}

// The passes a frame skipped, beside those of what the scene does not have (skinned or
// morphing meshes) or the method does not run (curved paths, the reveal beside shutter rays,
// the shutter rays in the paper's hybrid): those are skipped even when every pass is asked to run.
std::vector<std::string> skippedPasses(const RenderResult& result) {
  std::vector<std::string> names;
  for (const PlannedPass& pass : result.plan.passes())
    if (!pass.run && pass.reason != kNoDeformationReason && pass.reason != passes::kStraightPathsReason &&
        pass.reason != passes::kRevealLeftToShutterRaysReason && pass.reason != passes::kShutterRaysOffReason &&
        pass.reason != passes::kMovingTilesListedByTileMaxReason && pass.reason != passes::kNoRayBudgetReason &&
        !pass.reason.starts_with(passes::kVisibilitySchemeReason))
      names.push_back(pass.name);
  return names;
}

TEST(AnythingMovesOnScreenTest, FollowsTheSceneAnimation) {
  const scene::Scene room = scene::loadScene("living-room");
  EXPECT_TRUE(anythingMovesOnScreen(room, kMovingTime));
  EXPECT_FALSE(anythingMovesOnScreen(room, kStillTime));
  EXPECT_TRUE(anythingMovesOnScreen(room, 0.4f + 0.5f / room.settings.fps));  // the previous frame still moved
  EXPECT_TRUE(anythingMovesOnScreen(scene::loadScene("bistro"), 1.0f));       // the camera moves
  EXPECT_FALSE(anythingMovesOnScreen(scene::Scene{}, 0.0f));
}

TEST_F(FramePlanSkipsTest, AStillFrameSkipsTheBlurAndTheImageIsUnchanged) {
  Renderer renderer(context());
  const scene::Scene room = scene::loadScene("living-room");
  for (const char* method : {"postprocess", "hybrid", "hybrid-rays"}) {
    const RenderResult skipped = renderAt(renderer, room, method, kStillTime, true);
    const RenderResult everything = renderAt(renderer, room, method, kStillTime, false);
    EXPECT_TRUE(skippedPasses(everything).empty()) << method;
    const std::vector<std::string> names = skippedPasses(skipped);
    for (const char* pass : {"tile-max", "neighbor-max"})
      EXPECT_NE(std::find(names.begin(), names.end(), pass), names.end()) << method << " " << pass;
    const std::vector<std::string> blur = std::string(method).starts_with("hybrid")
                                              ? std::vector<std::string>{"hybrid-bvh-meshes", "ray-reveal", "gather", "composite"}
                                              : std::vector<std::string>{"gather"};
    for (const std::string& pass : blur)
      EXPECT_NE(std::find(names.begin(), names.end(), pass), names.end()) << method << " " << pass;
    for (const PlannedPass& pass : skipped.plan.passes())
      if (!pass.run) {
        EXPECT_FALSE(pass.reason.empty()) << pass.name;
        EXPECT_FALSE(pass.milliseconds.has_value()) << pass.name;
      }
    EXPECT_TRUE(skipped.plan.runs("resolve-gbuffer")) << method;

    // Every layer, bit for bit, and the display image.
    ASSERT_EQ(skipped.image.layers.size(), everything.image.layers.size()) << method;
    for (size_t i = 0; i < skipped.image.layers.size(); ++i) {
      const io::ImageLayer& a = skipped.image.layers[i];
      const io::ImageLayer& b = everything.image.layers[i];
      EXPECT_EQ(a.name, b.name) << method;
      EXPECT_EQ(a.values, b.values) << method << " layer '" << a.name << "'";
      EXPECT_EQ(a.ids, b.ids) << method << " layer '" << a.name << "'";
    }
    EXPECT_EQ(skipped.display.pixels, everything.display.pixels) << method;
    if (skipped.hybrid) {
      EXPECT_EQ(skipped.hybrid->maskPixels, 0u);
      EXPECT_EQ(everything.hybrid->maskPixels, 0u);
      EXPECT_EQ(everything.hybrid->revealRays, 0u);
      EXPECT_EQ(skipped.hybrid->settings.blur, everything.hybrid->settings.blur);
    }
    EXPECT_EQ(skipped.postprocess->effectiveForegroundBoost(), everything.postprocess->effectiveForegroundBoost());
    EXPECT_EQ(skipped.postprocess->foregroundBoostPixels, everything.postprocess->foregroundBoostPixels);
  }
}

TEST_F(FramePlanSkipsTest, AMovingFrameRunsTheBlur) {
  Renderer renderer(context());
  const scene::Scene room = scene::loadScene("living-room");
  for (const char* method : {"postprocess", "hybrid", "hybrid-rays"}) {
    const RenderResult result = renderAt(renderer, room, method, kMovingTime, true);
    EXPECT_TRUE(skippedPasses(result).empty()) << method;
    EXPECT_TRUE(result.plan.runs("tile-max")) << method;
  }
}

const PlannedPass* passNamed(const RenderResult& result, const std::string& name) {
  for (const PlannedPass& pass : result.plan.passes())
    if (pass.name == name) return &pass;
  return nullptr;
}

TEST_F(FramePlanSkipsTest, ASceneWithoutTexturesSkipsTheTexturePathAndTheImageIsUnchanged) {
  Renderer renderer(context());
  const scene::Scene temple = scene::loadScene("temple");
  ASSERT_FALSE(temple.textures.empty());
  scene::Scene plain = temple;
  for (scene::Material& material : plain.materials) material.baseColorTexture = -1;
  plain.textures.clear();
  const float time = plain.settings.frameTime;
  for (const char* method : {"sharp", "postprocess", "hybrid", "hybrid-rays", "reference"}) {
    const RenderResult textured = renderAt(renderer, temple, method, time, true);
    const PlannedPass* path = passNamed(textured, "texture-path");
    ASSERT_NE(path, nullptr) << method;
    EXPECT_TRUE(path->run) << method;
    EXPECT_NE(path->within.find(std::string(method) == "reference" ? "reference-accumulate-sample" : "resolve-gbuffer"),
              std::string::npos)
        << method << ": " << path->within;

    const RenderResult skipped = renderAt(renderer, plain, method, time, true);
    const RenderResult everything = renderAt(renderer, plain, method, time, false);
    path = passNamed(skipped, "texture-path");
    ASSERT_NE(path, nullptr) << method;
    EXPECT_FALSE(path->run) << method;
    EXPECT_FALSE(path->reason.empty()) << method;
    EXPECT_TRUE(passNamed(everything, "texture-path")->run) << method;
    if (std::string(method) == "hybrid-rays") {
      ASSERT_GT(skipped.hybrid->shutterRays, 0u);
    }
    ASSERT_EQ(skipped.image.layers.size(), everything.image.layers.size()) << method;
    for (size_t i = 0; i < skipped.image.layers.size(); ++i)
      EXPECT_EQ(skipped.image.layers[i].values, everything.image.layers[i].values)
          << method << " layer '" << skipped.image.layers[i].name << "'";
    EXPECT_EQ(skipped.display.pixels, everything.display.pixels) << method;
  }
}

// A wall that fills the view sliding along itself: every pixel moves, none has a silhouette.
scene::Scene slidingWall() {
  scene::procedural::SceneBuilder builder("sliding wall");
  const uint32_t material = builder.material("wall", glm::vec3(0.6f, 0.5f, 0.4f));
  const uint32_t mesh = builder.mesh(scene::procedural::makePlane(glm::vec2(400.0f, 400.0f), material));
  const glm::quat facingCamera = glm::angleAxis(std::numbers::pi_v<float> / 2.0f, glm::vec3(1, 0, 0));
  const uint32_t node = builder.object("wall", mesh, scene::procedural::makeTrs(glm::vec3(0, 0, -10), facingCamera));
  builder.translationKeys(node, {0.0f, 2.0f}, {glm::vec3(-10, 0, -10), glm::vec3(10, 0, -10)});
  builder.camera(glm::vec3(0.0f), glm::vec3(0, 0, -1), 0.9f);
  scene::Scene scene = builder.finish();
  scene.settings.frameTime = 1.0f;
  scene::deriveDefaults(scene);
  return scene;
}

// A scene of one instance traces it with no top level over it (HMB_SPEC_TRACE_TOP_LEVEL); the
// plan says so, and the images equal those of the full walk. The reference's rays hit the wall
// at every sample; the hybrid's reveal rays ignore it and find nothing behind it.
TEST_F(FramePlanSkipsTest, ASceneOfOneInstanceSkipsTheTopLevelWalkAndTheImageIsUnchanged) {
  Renderer renderer(context());
  const scene::Scene wall = slidingWall();
  ASSERT_EQ(wall.instances.size(), 1u);
  for (const char* method : {"hybrid", "hybrid-rays", "reference"}) {
    const RenderResult skipped = renderAt(renderer, wall, method, 1.0f, true);
    const RenderResult everything = renderAt(renderer, wall, method, 1.0f, false);
    const PlannedPass* walk = passNamed(skipped, "top-level-walk");
    ASSERT_NE(walk, nullptr) << method;
    EXPECT_FALSE(walk->run) << method;
    EXPECT_NE(walk->reason.find("one instance"), std::string::npos) << method << ": " << walk->reason;
    ASSERT_NE(passNamed(everything, "top-level-walk"), nullptr) << method;
    EXPECT_TRUE(passNamed(everything, "top-level-walk")->run) << method;
    EXPECT_EQ(skipped.display.pixels, everything.display.pixels) << method;
  }
  // A scene of many instances walks its top level inside the passes that trace.
  const RenderResult room = renderAt(renderer, scene::loadScene("living-room"), "reference", kMovingTime, true);
  const PlannedPass* walk = passNamed(room, "top-level-walk");
  ASSERT_NE(walk, nullptr);
  EXPECT_TRUE(walk->run);
  EXPECT_EQ(walk->within, "reference-accumulate-sample");
}

// A still frame asked for curved paths leaves the path passes out because nothing moves, not
// because the blur is straight; with every pass run, they run.
TEST_F(FramePlanSkipsTest, AStillFrameLeavesTheCurvedPathsOutAndSaysWhy) {
  Renderer renderer(context());
  const scene::Scene room = scene::loadScene("living-room");
  for (const char* method : {"postprocess", "hybrid", "hybrid-rays"})
    for (const bool skip : {true, false}) {
      const RenderResult result = renderAt(renderer, room, method, kStillTime, skip, passes::MotionPath::Curved);
      for (const char* name : {passes::ShutterPathPass::kTransformName, passes::ShutterPathPass::kResolveName}) {
        const PlannedPass* pass = passNamed(result, name);
        ASSERT_NE(pass, nullptr) << method << " " << name;
        EXPECT_EQ(pass->run, !skip) << method << " " << name;
        EXPECT_EQ(pass->reason, skip ? std::string(passes::kStillPathsReason) : std::string()) << method << " " << name;
      }
    }
}

std::string noWorkOf(const RenderResult& result, const std::string& name) {
  for (const PlannedPass& pass : result.plan.passes())
    if (pass.name == name) return pass.noWork;
  return "(no such pass)";
}

TEST_F(FramePlanSkipsTest, AnEmptyRayMaskTracesNothingAndTheReportSaysSo) {
  Renderer renderer(context());
  const scene::Scene wall = slidingWall();
  ASSERT_TRUE(anythingMovesOnScreen(wall, 1.0f));
  const RenderResult result = renderAt(renderer, wall, "hybrid", 1.0f, true);
  // The wall has no texture, and is the scene's one instance (the shutter rays' passes, which the
  // paper's method never runs, are left out of skippedPasses).
  EXPECT_EQ(skippedPasses(result), (std::vector<std::string>{"texture-path", "top-level-walk"}));
  EXPECT_EQ(result.hybrid->edgeCandidates, 0u);
  EXPECT_EQ(result.hybrid->maskPixels, 0u);
  EXPECT_EQ(result.hybrid->revealRays, 0u);
  for (const char* pass : {"ray-mask-edges", "ray-reveal", "gather-background", "composite"})
    EXPECT_FALSE(noWorkOf(result, pass).empty()) << pass;
  EXPECT_TRUE(noWorkOf(result, "gather").empty());

  // A frame with silhouettes has work in every pass; the coverage composite's pass takes the
  // mask pixels left unrevealed (the background gather blends the others), and says so when
  // there are none.
  const RenderResult room = renderAt(renderer, scene::loadScene("living-room"), "hybrid", kMovingTime, true);
  ASSERT_GT(room.hybrid->revealRays, 0u);
  const bool allRevealed = room.hybrid->maskPixels == room.hybrid->revealedPixels;
  for (const PlannedPass& pass : room.plan.passes())
    EXPECT_EQ(pass.noWork.empty(), !(pass.name == "composite" && allRevealed)) << pass.name;
}

// With shutter rays (hybrid-rays), the ray mask's own passes, the reveal and the composite are
// skipped and say why; the moving tiles are still listed for the rays, which trace.
TEST_F(FramePlanSkipsTest, ShutterRaysLeaveTheRevealOutAndSayWhy) {
  Renderer renderer(context());
  const RenderResult room = renderAt(renderer, scene::loadScene("living-room"), "hybrid-rays", kMovingTime, true);
  for (const char* name :
       {"ray-mask-edges", "ray-mask-range-blocks", "ray-mask-range-check", "ray-reveal",
        "gather-background", "composite"}) {
    const PlannedPass* pass = passNamed(room, name);
    ASSERT_NE(pass, nullptr) << name;
    EXPECT_FALSE(pass->run) << name;
    EXPECT_EQ(pass->reason, passes::kRevealLeftToShutterRaysReason) << name;
  }
  for (const char* name : {"ray-mask-moving-tiles", "shutter-rays-list", "gather", "shutter-rays-trace"})
    EXPECT_TRUE(room.plan.runs(name)) << name;
  EXPECT_EQ(room.hybrid->maskPixels, 0u);
  EXPECT_EQ(room.hybrid->revealRays, 0u);
  EXPECT_GT(room.hybrid->shutterRays, 0u);
  // Nor are their buffers made: the mask's edges, mask, list and candidates (16 bytes a pixel)
  // and the revealed layer and its blur (48), less the rays' own list (4); at 640x360 the
  // per-pixel buffers outweigh the trace scene's.
  RenderSettings settings;
  settings.method = Method::HybridRays;
  settings.width = 640;
  settings.height = 360;
  settings.frameTime = kMovingTime;
  const RenderResult rays = renderer.render(scene::loadScene("living-room"), settings);
  settings.method = Method::Hybrid;
  const RenderResult paper = renderer.render(scene::loadScene("living-room"), settings);
  const uint64_t pixels = uint64_t(settings.width) * settings.height;
  EXPECT_LE(rays.memory.peakBytes + 56 * pixels, paper.memory.peakBytes)
      << rays.memory.peakBytes << " bytes beside the rays, " << paper.memory.peakBytes << " without";
}

}  // namespace
}  // namespace hmb::test
