// The resolved G-buffer against analytic answers: camera-space depth and normal of a tilted
// plane, screen velocity of a translating quad (closed form) and of a rotating, tilted plane
// seen by a moving camera (each pixel's surface point re-projected at the previous frame in
// double precision, which only perspective-correct interpolation matches), object ids, the
// background, and both visibility schemes giving the same G-buffer.
#include <cmath>
#include <numbers>

#include <glm/glm.hpp>
#include <glm/packing.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "hmblur/load_scene.h"
#include "kernels/gbuffer/gbuffer_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/scene_builder.h"
#include "tests/raster/raster_harness.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using passes::VisibilityScheme;
using scene::procedural::SceneBuilder;
using scene::procedural::makePlane;
using scene::procedural::makeTrs;

constexpr uint32_t kWidth = 97, kHeight = 61;  // odd sizes: no tile or group divides them
constexpr float kFps = 100.0f;
constexpr float kTime = 0.5f;

// A plane of the given size facing +Z at rest (makePlane faces +Y).
glm::quat facingPlusZ() { return glm::angleAxis(std::numbers::pi_v<float> / 2.0f, glm::vec3(1, 0, 0)); }

struct PlaneScene {
  scene::Scene scene;
  uint32_t objectId = 0;
};

// A large plane, rotated by `tilt` about Y on top of facing +Z, optionally translating and
// spinning; the camera at `eye` looks down -Z and may move along +X.
PlaneScene planeScene(float tiltRadians, glm::vec3 velocity, float spinTurnsPerSecond, float cameraSpeed,
                      bool doubleSided = false) {
  SceneBuilder builder("analytic plane");
  const uint32_t material = builder.material("grey", glm::vec3(0.5f), -1, doubleSided);
  const uint32_t mesh = builder.mesh(makePlane(glm::vec2(6.0f, 6.0f), material));
  const glm::quat rest = glm::angleAxis(tiltRadians, glm::vec3(0, 1, 0)) * facingPlusZ();
  const glm::vec3 centre(0.0f, 0.0f, -5.0f);
  const uint32_t node = builder.object("plane", mesh, makeTrs(centre, rest));
  if (velocity != glm::vec3(0.0f))
    builder.translationKeys(node, {0.0f, 1.0f}, {centre, centre + velocity});
  if (spinTurnsPerSecond != 0.0f) builder.spin(node, glm::vec3(0, 0, 1), spinTurnsPerSecond, 0.0f, 1.0f);
  const uint32_t cameraNode = builder.camera(glm::vec3(0.0f), glm::vec3(0, 0, -1), 0.9f);
  if (cameraSpeed != 0.0f)
    builder.translationKeys(cameraNode, {0.0f, 1.0f}, {glm::vec3(0.0f), glm::vec3(cameraSpeed, 0.0f, 0.0f)});
  PlaneScene out{builder.finish(), 0};
  out.scene.settings.fps = kFps;
  out.scene.settings.frameTime = kTime;
  scene::deriveDefaults(out.scene);
  out.objectId = out.scene.instances.at(0).objectId;
  return out;
}

// The world-space ray through the centre of pixel (x, y) for a camera (y down in the image).
struct Ray {
  glm::dvec3 origin, direction;
};

Ray pixelRay(const FrameCamera& camera, uint32_t x, uint32_t y) {
  const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjCurrent));
  const double ndcX = (x + 0.5) / kWidth * 2.0 - 1.0, ndcY = (y + 0.5) / kHeight * 2.0 - 1.0;
  // Depth is reversed: z/w = 1 at the near plane, 0 at the far one.
  const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
  const glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 0.0, 1.0);
  const glm::dvec3 a = glm::dvec3(nearPoint) / nearPoint.w, b = glm::dvec3(farPoint) / farPoint.w;
  return {a, glm::normalize(b - a)};
}

// The object-space point of the plane (local y = 0 of makePlane) that pixel (x, y) sees at t.
bool hitPlane(const scene::Scene& scene, const FrameCamera& camera, uint32_t x, uint32_t y, glm::dvec3& objectPoint,
              glm::dvec3& worldPoint, glm::dvec3& worldNormal) {
  const glm::dmat4 world = glm::dmat4(scene.worldMatrixAt(scene.instances[0].node, kTime));
  const glm::dmat4 toObject = glm::inverse(world);
  const Ray ray = pixelRay(camera, x, y);
  const glm::dvec3 o = glm::dvec3(toObject * glm::dvec4(ray.origin, 1.0));
  const glm::dvec3 d = glm::dvec3(toObject * glm::dvec4(ray.direction, 0.0));
  if (std::abs(d.y) < 1e-12) return false;
  const double s = -o.y / d.y;
  if (s <= 0.0) return false;
  objectPoint = o + s * d;
  if (std::abs(objectPoint.x) > 3.0 || std::abs(objectPoint.z) > 3.0) return false;
  worldPoint = glm::dvec3(world * glm::dvec4(objectPoint, 1.0));
  worldNormal = glm::normalize(glm::dvec3(glm::transpose(toObject) * glm::dvec4(0.0, 1.0, 0.0, 0.0)));
  return true;
}

glm::dvec2 project(const glm::mat4& viewProj, const glm::dvec3& world) {
  const glm::dvec4 clip = glm::dmat4(viewProj) * glm::dvec4(world, 1.0);
  return {(clip.x / clip.w * 0.5 + 0.5) * kWidth, (clip.y / clip.w * 0.5 + 0.5) * kHeight};
}

// Pixels well inside the plane (away from its silhouette, where coverage may differ by a pixel).
bool interior(const scene::Scene& scene, const FrameCamera& camera, uint32_t x, uint32_t y) {
  glm::dvec3 o, w, n;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int px = int(x) + dx, py = int(y) + dy;
      if (px < 0 || py < 0 || px >= int(kWidth) || py >= int(kHeight)) continue;
      if (!hitPlane(scene, camera, uint32_t(px), uint32_t(py), o, w, n)) return false;
    }
  return true;
}

using GBufferAnalyticTest = VulkanTest;

TEST_F(GBufferAnalyticTest, DepthAndNormalOfATiltedPlaneAreExact) {
  const PlaneScene plane = planeScene(0.7f, glm::vec3(0.0f), 0.0f, 0.0f);
  const FrameCamera camera = frameCamera(plane.scene, kTime, kWidth, kHeight);
  const GBufferReadback g = renderGBuffer(context(), plane.scene, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics);
  size_t checked = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      if (!interior(plane.scene, camera, x, y)) continue;
      glm::dvec3 objectPoint, worldPoint, worldNormal;
      ASSERT_TRUE(hitPlane(plane.scene, camera, x, y, objectPoint, worldPoint, worldNormal));
      const glm::vec4 nd = g.normalDepth[size_t(y) * kWidth + x];
      const double depth = -(glm::dmat4(camera.view) * glm::dvec4(worldPoint, 1.0)).z;
      EXPECT_NEAR(nd.w, depth, 1e-4 * depth) << x << "," << y;
      EXPECT_GT(glm::dot(glm::dvec3(nd), worldNormal), 1.0 - 1e-5) << x << "," << y;
      EXPECT_EQ(g.objectId[size_t(y) * kWidth + x], plane.objectId);
      ++checked;
    }
  EXPECT_GT(checked, size_t(kWidth) * kHeight / 4);
}

TEST_F(GBufferAnalyticTest, TranslatingQuadMovesByFocalLengthOverDepth) {
  const glm::vec3 velocity(1.5f, -0.8f, 0.0f);  // world units per second
  const PlaneScene plane = planeScene(0.0f, velocity, 0.0f, 0.0f);
  const FrameCamera camera = frameCamera(plane.scene, kTime, kWidth, kHeight);
  const GBufferReadback g = renderGBuffer(context(), plane.scene, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics);
  // Pixels per world unit at depth 5: (height / 2) / tan(yfov / 2) / 5; image y points down.
  const double pixelsPerUnit = (kHeight / 2.0) / std::tan(0.9 / 2.0) / 5.0;
  const glm::dvec2 expected(velocity.x / kFps * pixelsPerUnit, -velocity.y / kFps * pixelsPerUnit);
  size_t checked = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      if (!interior(plane.scene, camera, x, y)) continue;
      const glm::vec2 v = g.velocity[size_t(y) * kWidth + x];
      EXPECT_NEAR(v.x, expected.x, 2e-3) << x << "," << y;
      EXPECT_NEAR(v.y, expected.y, 2e-3) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, size_t(kWidth) * kHeight / 2);
}

TEST_F(GBufferAnalyticTest, VelocityOfARotatingTiltedPlaneUnderAMovingCameraIsPerspectiveCorrect) {
  const PlaneScene plane = planeScene(1.0f, glm::vec3(0.3f, 0.2f, 1.0f), 0.4f, 0.9f);
  const FrameCamera camera = frameCamera(plane.scene, kTime, kWidth, kHeight);
  const GBufferReadback g = renderGBuffer(context(), plane.scene, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics);
  const glm::dmat4 worldPrevious =
      glm::dmat4(plane.scene.worldMatrixAt(plane.scene.instances[0].node, kTime - 1.0f / kFps));
  size_t checked = 0;
  double largest = 0.0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      if (!interior(plane.scene, camera, x, y)) continue;
      glm::dvec3 objectPoint, worldPoint, worldNormal;
      ASSERT_TRUE(hitPlane(plane.scene, camera, x, y, objectPoint, worldPoint, worldNormal));
      const glm::dvec3 previousWorld = glm::dvec3(worldPrevious * glm::dvec4(objectPoint, 1.0));
      const glm::dvec2 expected = glm::dvec2(x + 0.5, y + 0.5) - project(camera.viewProjPrevious, previousWorld);
      const glm::vec2 v = g.velocity[size_t(y) * kWidth + x];
      largest = std::max(largest, glm::length(expected));
      EXPECT_NEAR(v.x, expected.x, 5e-3 + 1e-3 * std::abs(expected.x)) << x << "," << y;
      EXPECT_NEAR(v.y, expected.y, 5e-3 + 1e-3 * std::abs(expected.y)) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, size_t(kWidth) * kHeight / 4);
  EXPECT_GT(largest, 1.0) << "the motion should be large enough to tell interpolation schemes apart";
}

// The curved path's records (resolve_shutter_path): each pixel's surface point re-projected at
// mid-shutter and shutter open, object and camera both moving, in double precision; the
// background has none.
TEST_F(GBufferAnalyticTest, ShutterPathsOfARotatingTiltedPlaneUnderAMovingCameraAreExact) {
  PlaneScene plane = planeScene(1.0f, glm::vec3(0.3f, 0.2f, 1.0f), 6.0f, 0.9f);
  plane.scene.settings.exposure = 1.5f / kFps;  // past the previous frame: the path is not the velocity's
  const scene::Scene& s = plane.scene;
  const FrameCamera camera = frameCamera(s, kTime, kWidth, kHeight);
  const GBufferReadback g = renderGBuffer(context(), s, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics, true);
  ASSERT_EQ(g.shutterPaths.size(), size_t(kWidth) * kHeight);
  const float tMid = kTime - 0.5f * s.settings.exposure, tOpen = kTime - s.settings.exposure;
  const glm::dmat4 worldMid = glm::dmat4(s.worldMatrixAt(s.instances[0].node, tMid));
  const glm::dmat4 worldOpen = glm::dmat4(s.worldMatrixAt(s.instances[0].node, tOpen));
  const glm::mat4 viewProjMid = frameCamera(s, tMid, kWidth, kHeight).viewProjCurrent;
  const glm::mat4 viewProjOpen = frameCamera(s, tOpen, kWidth, kHeight).viewProjCurrent;
  size_t checked = 0, background = 0;
  double bend = 0.0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const glm::uvec2 record = g.shutterPaths[size_t(y) * kWidth + x];
      if (g.visibility.entries[size_t(y) * kWidth + x].x == HMB_VIS_EMPTY) {
        EXPECT_EQ(record, glm::uvec2(HMB_NO_SHUTTER_PATH)) << x << "," << y;
        ++background;
        continue;
      }
      if (!interior(s, camera, x, y)) continue;
      glm::dvec3 objectPoint, worldPoint, worldNormal;
      ASSERT_TRUE(hitPlane(s, camera, x, y, objectPoint, worldPoint, worldNormal));
      const glm::dvec2 centre(x + 0.5, y + 0.5);
      const glm::dvec2 fromMid = centre - project(viewProjMid, glm::dvec3(worldMid * glm::dvec4(objectPoint, 1.0)));
      const glm::dvec2 fromOpen = centre - project(viewProjOpen, glm::dvec3(worldOpen * glm::dvec4(objectPoint, 1.0)));
      const glm::vec2 mid = glm::unpackHalf2x16(record.x), open = glm::unpackHalf2x16(record.y);
      for (int c = 0; c < 2; ++c) {
        EXPECT_NEAR(mid[c], fromMid[c], 1e-2 + 2e-3 * std::abs(fromMid[c])) << x << "," << y;
        EXPECT_NEAR(open[c], fromOpen[c], 1e-2 + 2e-3 * std::abs(fromOpen[c])) << x << "," << y;
      }
      bend = std::max(bend, glm::length(fromMid - 0.5 * fromOpen));
      ++checked;
    }
  EXPECT_GT(checked, size_t(kWidth) * kHeight / 4);
  EXPECT_GT(background, 0u);
  EXPECT_GT(bend, 1.0) << "the path should bend enough to tell it from a straight line";
}

TEST_F(GBufferAnalyticTest, BackgroundIsEmptyFarAndStill) {
  const PlaneScene plane = planeScene(1.2f, glm::vec3(0.0f), 0.0f, 0.0f);
  const FrameCamera camera = frameCamera(plane.scene, kTime, kWidth, kHeight);
  const GBufferReadback g = renderGBuffer(context(), plane.scene, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics);
  size_t background = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t(y) * kWidth + x;
      glm::dvec3 o, w, n;
      const bool hit = hitPlane(plane.scene, camera, x, y, o, w, n);
      if (g.visibility.entries[i].x != HMB_VIS_EMPTY) {
        for (int c = 0; c < 4; ++c) EXPECT_TRUE(std::isfinite(g.color[i][c]));
        continue;
      }
      EXPECT_FALSE(hit && interior(plane.scene, camera, x, y)) << "hole at " << x << "," << y;
      EXPECT_EQ(g.objectId[i], 0u);
      EXPECT_EQ(g.normalDepth[i].w, camera.zfar);
      EXPECT_EQ(g.velocity[i], glm::vec2(0.0f));
      EXPECT_EQ(g.color[i].a, 1.0f);
      ++background;
    }
  EXPECT_GT(background, 0u) << "the tilted plane should leave some background";
}

TEST_F(GBufferAnalyticTest, BackFacesAreCulledUnlessDoubleSidedAndThenFaceTheViewer) {
  // Tilted past 90 degrees the plane shows its back to the camera.
  const PlaneScene single = planeScene(2.4f, glm::vec3(0.0f), 0.0f, 0.0f, false);
  const PlaneScene twoSided = planeScene(2.4f, glm::vec3(0.0f), 0.0f, 0.0f, true);
  const GBufferReadback culled = renderGBuffer(context(), single.scene, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics);
  const GBufferReadback shown = renderGBuffer(context(), twoSided.scene, kTime, kWidth, kHeight, VisibilityScheme::Int64Atomics);
  const FrameCamera camera = frameCamera(twoSided.scene, kTime, kWidth, kHeight);
  size_t covered = 0;
  for (size_t i = 0; i < culled.objectId.size(); ++i) {
    EXPECT_EQ(culled.objectId[i], 0u);
    if (shown.objectId[i] == 0) continue;
    ++covered;
    // The shading normal points towards the eye.
    const uint32_t x = uint32_t(i % kWidth), y = uint32_t(i / kWidth);
    const Ray ray = pixelRay(camera, x, y);
    EXPECT_LT(glm::dot(glm::dvec3(glm::vec3(shown.normalDepth[i])), ray.direction), 0.0);
  }
  EXPECT_GT(covered, shown.objectId.size() / 8);
}

TEST_F(GBufferAnalyticTest, BothVisibilitySchemesGiveTheSameGBuffer) {
  const scene::Scene scene = scene::loadScene("temple");
  const GBufferReadback a = renderGBuffer(context(), scene, scene.settings.frameTime, 160, 90, VisibilityScheme::Int64Atomics);
  const GBufferReadback b = renderGBuffer(context(), scene, scene.settings.frameTime, 160, 90, VisibilityScheme::Depth32TwoPass);
  EXPECT_EQ(a.visibility.entries, b.visibility.entries);
  EXPECT_EQ(a.objectId, b.objectId);
  EXPECT_EQ(a.velocity, b.velocity);
  EXPECT_EQ(a.normalDepth, b.normalDepth);
  EXPECT_EQ(a.color, b.color);
}

}  // namespace
}  // namespace hmb::test
