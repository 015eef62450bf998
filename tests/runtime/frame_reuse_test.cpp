// A renderer keeps what one frame built while it still serves the next (the hybrid's mesh
// trees and top-level tree, or its still instances' part of it, the reference's mesh trees),
// says so in the plan, and the frame it renders is bit for bit the frame a fresh renderer makes.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "hmblur/load_scene.h"
#include "hmblur/renderer.h"
#include "runtime/device_scene/trace_scene.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using FrameReuseTest = VulkanTest;

constexpr const char* kMeshes = "hybrid-bvh-meshes";
constexpr const char* kInstances = "hybrid-bvh-instances";

RenderResult renderWith(const std::string& method, Renderer& renderer, const scene::Scene& scene, float time,
                        bool reuse = true) {
  RenderSettings settings;
  settings.method = parseMethod(method);
  settings.width = 96;
  settings.height = 54;
  settings.frameTime = time;
  settings.reference.samplesPerPixel = 4;
  settings.reuseAcrossFrames = reuse;
  return renderer.render(scene, settings);
}

RenderResult renderHybrid(Renderer& renderer, const scene::Scene& scene, float time, bool reuse = true) {
  return renderWith("hybrid-rays", renderer, scene, time, reuse);
}
RenderResult renderReference(Renderer& renderer, const scene::Scene& scene, float time, bool reuse = true) {
  return renderWith("reference", renderer, scene, time, reuse);
}

const PlannedPass& passNamed(const RenderResult& result, const std::string& name) {
  const auto& passes = result.plan.passes();
  const auto it = std::find_if(passes.begin(), passes.end(), [&](const PlannedPass& p) { return p.name == name; });
  if (it == passes.end()) throw std::runtime_error("no pass " + name);
  return *it;
}

void expectSameImage(const RenderResult& a, const RenderResult& b) {
  ASSERT_EQ(a.image.layers.size(), b.image.layers.size());
  for (size_t i = 0; i < a.image.layers.size(); ++i) {
    EXPECT_EQ(a.image.layers[i].values, b.image.layers[i].values) << "layer '" << a.image.layers[i].name << "'";
    EXPECT_EQ(a.image.layers[i].ids, b.image.layers[i].ids) << "layer '" << a.image.layers[i].name << "'";
  }
  EXPECT_EQ(a.display.pixels, b.display.pixels);
}

// Bistro with its camera's animation only: the tray and the fan stay where they are.
scene::Scene bistroWithOnlyTheCameraMoving() {
  scene::Scene scene = scene::loadScene("bistro");
  const int32_t cameraNode = scene.camera.value().node;
  std::erase_if(scene.channels, [&](const scene::AnimationChannel& c) { return int32_t(c.node) != cameraNode; });
  return scene;
}

// A pass the plan skips because what an earlier frame built serves: it says why, and has no time.
void expectKept(const RenderResult& result, const std::string& name) {
  EXPECT_FALSE(passNamed(result, name).run) << name;
  EXPECT_FALSE(passNamed(result, name).reason.empty()) << name;
  EXPECT_FALSE(passNamed(result, name).milliseconds.has_value()) << name;
}

// The hybrid's frames at t = 1 and one frame later, by one renderer; and the later one by a
// fresh renderer, whose image the kept trees must give.
struct TwoFrames {
  RenderResult before, after, alone;
};
TwoFrames renderTwoFrames(vk::Context& context, const scene::Scene& scene) {
  const float first = 1.0f, second = 1.0f + 1.0f / scene.settings.fps;
  Renderer sequence(context), fresh(context);
  TwoFrames frames;
  frames.before = renderHybrid(sequence, scene, first);
  frames.after = renderHybrid(sequence, scene, second);
  frames.alone = renderHybrid(fresh, scene, second);
  return frames;
}

TEST_F(FrameReuseTest, MovingInstancesRebuildTheTopLevelOnly) {
  const TwoFrames frames = renderTwoFrames(context(), scene::loadScene("temple"));
  EXPECT_TRUE(passNamed(frames.before, kMeshes).run);
  EXPECT_TRUE(passNamed(frames.before, kInstances).run);
  expectKept(frames.after, kMeshes);
  EXPECT_TRUE(passNamed(frames.after, kInstances).run);
  EXPECT_FALSE(frames.after.hybrid->setupMilliseconds.has_value());
  ASSERT_GT(frames.after.hybrid->shutterRays, 0u);
  expectSameImage(frames.after, frames.alone);
}

// Bistro's tray and fan move among 315 still instances: the first frame builds the still ones'
// tree as scene setup (TraceScene::splitTopLevel), and the next keeps it and inserts the moving
// ones alone, to the image a fresh renderer makes.
TEST_F(FrameReuseTest, MovingInstancesAmongStillOnesAreInsertedIntoTheKeptTree) {
  constexpr const char* kStill = "hybrid-bvh-still-instances";
  const scene::Scene bistro = scene::loadScene("bistro");
  ASSERT_EQ(TraceScene::whyNotSplit(bistro, TraceScene::kStillInstancesToSplit), "");
  const TwoFrames frames = renderTwoFrames(context(), bistro);
  for (const char* pass : {kStill, kInstances}) EXPECT_TRUE(passNamed(frames.before, pass).run) << pass;
  expectKept(frames.after, kStill);
  EXPECT_TRUE(passNamed(frames.after, kInstances).run);
  EXPECT_FALSE(frames.after.hybrid->setupMilliseconds.has_value());
  EXPECT_TRUE(passNamed(frames.alone, kStill).run);
  expectSameImage(frames.after, frames.alone);
}

TEST_F(FrameReuseTest, AMovingCameraOverStillInstancesKeepsBothTrees) {
  const scene::Scene bistro = bistroWithOnlyTheCameraMoving();
  const float first = 1.0f, second = 1.0f + 1.0f / bistro.settings.fps;
  Renderer sequence(context());
  renderHybrid(sequence, bistro, first);
  const RenderResult after = renderHybrid(sequence, bistro, second);
  EXPECT_FALSE(passNamed(after, kMeshes).run);
  EXPECT_FALSE(passNamed(after, kInstances).run);
  EXPECT_FALSE(passNamed(after, kInstances).reason.empty());
  ASSERT_GT(after.hybrid->shutterRays, 0u);

  Renderer fresh(context());
  const RenderResult alone = renderHybrid(fresh, bistro, second);
  EXPECT_TRUE(passNamed(alone, kInstances).run);
  expectSameImage(after, alone);
}

TEST_F(FrameReuseTest, ChangedMeshesOrReuseOffBuildEverything) {
  scene::Scene bistro = bistroWithOnlyTheCameraMoving();
  Renderer renderer(context());
  renderHybrid(renderer, bistro, 1.0f);
  const RenderResult off = renderHybrid(renderer, bistro, 1.0f, false);
  EXPECT_TRUE(passNamed(off, kMeshes).run);
  EXPECT_TRUE(passNamed(off, kInstances).run);

  // One vertex of one mesh moved: another fingerprint, so the trees are built again.
  bistro.meshes.back().positions.front().x += 0.01f;
  const RenderResult changed = renderHybrid(renderer, bistro, 1.0f);
  EXPECT_TRUE(passNamed(changed, kMeshes).run);
  EXPECT_TRUE(passNamed(changed, kInstances).run);
  Renderer fresh(context());
  expectSameImage(changed, renderHybrid(fresh, bistro, 1.0f));
}

TEST_F(FrameReuseTest, TheReferenceKeepsItsMeshTreesAcrossFrames) {
  constexpr const char* kReferenceMeshes = "reference-bvh-meshes";
  const scene::Scene temple = scene::loadScene("temple");
  const float first = 1.0f, second = 1.0f + 1.0f / temple.settings.fps;
  Renderer sequence(context());
  EXPECT_TRUE(passNamed(renderReference(sequence, temple, first), kReferenceMeshes).run);
  const RenderResult after = renderReference(sequence, temple, second);
  EXPECT_FALSE(passNamed(after, kReferenceMeshes).run);
  EXPECT_FALSE(passNamed(after, kReferenceMeshes).reason.empty());
  EXPECT_FALSE(passNamed(after, kReferenceMeshes).milliseconds.has_value());
  EXPECT_TRUE(passNamed(after, "reference-bvh-instances").run);

  Renderer fresh(context());
  expectSameImage(after, renderReference(fresh, temple, second));
  EXPECT_TRUE(passNamed(renderReference(sequence, temple, second, false), kReferenceMeshes).run);
}

}  // namespace
}  // namespace hmb::test
