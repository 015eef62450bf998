// reveal_background.comp on an analytic scene: a tilted far plane (object A, one flat colour)
// partly behind a small quad (object B) in front of it, moving sideways. Through B the reveal
// must find A: its id, its camera depth and normal (ray-plane intersection in double), its
// shaded colour, its velocity (zero for a still plane under a still camera, the re-projection
// of the same surface point otherwise); where nothing lies behind, id 0 at the far depth.
// Both stop modes, the recursion bound of the luminance mode, the pixels left unlisted, and
// the whole hybrid render's mask and revealed layers.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>

#include "hmblur/renderer.h"
#include "kernels/ray_mask/ray_mask_layout.h"
#include "kernels/shutter_rays/shutter_rays_layout.h"
#include "scenes/procedural/mesh_builders.h"
#include "scenes/procedural/scene_builder.h"
#include "tests/hybrid/hybrid_harness.h"
#include "tests/mblur/mblur_harness.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using namespace hybrid;
using passes::HybridSettings;
using passes::RevealStop;
using scene::procedural::makePlane;
using scene::procedural::makeTrs;
using scene::procedural::SceneBuilder;

constexpr uint32_t kWidth = 80, kHeight = 60;
constexpr float kFps = 60.0f;
constexpr float kTime = 0.5f;
const glm::vec3 kColorA(0.2f, 0.5f, 0.8f);
const glm::vec3 kColorB(0.9f, 0.1f, 0.1f);

glm::quat facingPlusZ() { return glm::angleAxis(std::numbers::pi_v<float> / 2.0f, glm::vec3(1, 0, 0)); }

struct Quad {
  uint32_t node = 0;
  uint32_t objectId = 0;
  glm::dvec2 half;  // half size in the plane's object x and z
};

struct RevealScene {
  scene::Scene scene;
  Quad a, b;
};

// A: an 8 x 8 plane tilted 0.35 rad about Y, centred at (-2, 0, -10) at the frame time, its
// right edge inside the view; B: a 2 x 2 quad at depth 4 straddling A's right edge, moving
// along -X at 12 units per second (about 3 px per frame). The camera at the origin looks
// down -Z.
RevealScene revealScene(glm::vec3 colorB = kColorB, glm::vec3 velocityA = glm::vec3(0.0f)) {
  SceneBuilder builder("reveal");
  const uint32_t materialA = builder.material("A", kColorA);
  const uint32_t materialB = builder.material("B", colorB);
  const uint32_t meshA = builder.mesh(makePlane(glm::vec2(8.0f, 8.0f), materialA));
  const uint32_t meshB = builder.mesh(makePlane(glm::vec2(2.0f, 2.0f), materialB));
  const glm::vec3 centreA(-2.0f, 0.0f, -10.0f), centreB(1.0f, 0.0f, -4.0f);
  RevealScene out;
  out.a.node = builder.object("A", meshA, makeTrs(centreA, glm::angleAxis(0.35f, glm::vec3(0, 1, 0)) * facingPlusZ()));
  out.b.node = builder.object("B", meshB, makeTrs(centreB, facingPlusZ()));
  // Keys one second apart around the frame time.
  const glm::vec3 velocityB(-12.0f, 0.0f, 0.0f);
  builder.translationKeys(out.b.node, {kTime - 0.5f, kTime + 0.5f},
                          {centreB - 0.5f * velocityB, centreB + 0.5f * velocityB});
  if (velocityA != glm::vec3(0.0f))
    builder.translationKeys(out.a.node, {kTime - 0.5f, kTime + 0.5f},
                            {centreA - 0.5f * velocityA, centreA + 0.5f * velocityA});
  builder.camera(glm::vec3(0.0f), glm::vec3(0, 0, -1), 0.9f);
  out.scene = builder.finish();
  out.scene.light.direction = glm::normalize(glm::vec3(0.3f, -0.5f, -0.8f));
  out.scene.light.color = glm::vec3(0.9f);
  out.scene.light.ambient = glm::vec3(0.1f);
  out.scene.settings.fps = kFps;
  out.scene.settings.frameTime = kTime;
  scene::deriveDefaults(out.scene);
  for (const scene::Instance& instance : out.scene.instances) {
    if (instance.node == out.a.node) out.a.objectId = instance.objectId;
    if (instance.node == out.b.node) out.b.objectId = instance.objectId;
  }
  out.a.half = {4.0, 4.0};
  out.b.half = {1.0, 1.0};
  return out;
}

// Where the ray through a pixel centre meets a quad (its object y = 0 plane) at time t.
struct QuadHit {
  bool hit = false;
  glm::dvec3 objectPoint{0.0}, worldPoint{0.0}, worldNormal{0.0};
  double depth = 0.0;
};

QuadHit hitQuad(const scene::Scene& scene, const FrameCamera& camera, const Quad& quad, double x, double y, float t) {
  const glm::dmat4 inverse = glm::inverse(glm::dmat4(camera.viewProjCurrent));
  const double ndcX = x / kWidth * 2.0 - 1.0, ndcY = y / kHeight * 2.0 - 1.0;
  // Depth is reversed: z/w = 1 at the near plane, 0 at the far one.
  const glm::dvec4 nearPoint = inverse * glm::dvec4(ndcX, ndcY, 1.0, 1.0);
  const glm::dvec4 farPoint = inverse * glm::dvec4(ndcX, ndcY, 0.0, 1.0);
  const glm::dvec3 origin = glm::dvec3(nearPoint) / nearPoint.w;
  const glm::dvec3 direction = glm::normalize(glm::dvec3(farPoint) / farPoint.w - origin);
  const glm::dmat4 world = glm::dmat4(scene.worldMatrixAt(quad.node, t));
  const glm::dmat4 toObject = glm::inverse(world);
  const glm::dvec3 o = glm::dvec3(toObject * glm::dvec4(origin, 1.0));
  const glm::dvec3 d = glm::dvec3(toObject * glm::dvec4(direction, 0.0));
  QuadHit h;
  if (std::abs(d.y) < 1e-12) return h;
  const double s = -o.y / d.y;
  h.objectPoint = o + s * d;
  if (s <= 0.0 || std::abs(h.objectPoint.x) > quad.half.x || std::abs(h.objectPoint.z) > quad.half.y) return h;
  h.hit = true;
  h.worldPoint = glm::dvec3(world * glm::dvec4(h.objectPoint, 1.0));
  h.worldNormal = glm::normalize(glm::dvec3(glm::transpose(toObject) * glm::dvec4(0.0, 1.0, 0.0, 0.0)));
  h.depth = -(glm::dmat4(camera.view) * glm::dvec4(h.worldPoint, 1.0)).z;
  return h;
}

enum class Coverage { Inside, Outside, Edge };

// Inside when the rays through the pixel and its 8 neighbours all meet the quad, outside when
// none does (a pixel away from the quad's silhouette, where raster and ray may disagree).
Coverage coverage(const scene::Scene& scene, const FrameCamera& camera, const Quad& quad, uint32_t x, uint32_t y) {
  int hits = 0;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) hits += hitQuad(scene, camera, quad, x + dx + 0.5, y + dy + 0.5, kTime).hit;
  return hits == 9 ? Coverage::Inside : hits == 0 ? Coverage::Outside : Coverage::Edge;
}

// Flat shading of A: albedo (ambient + light max(n . -L, 0)).
glm::dvec3 shadedA(const scene::Scene& scene, const glm::dvec3& normal) {
  const double lambert = std::max(glm::dot(normal, -glm::dvec3(glm::normalize(scene.light.direction))), 0.0);
  return glm::dvec3(kColorA) * (glm::dvec3(scene.light.ambient) + glm::dvec3(scene.light.color) * lambert);
}

std::vector<uint32_t> everyPixel() {
  std::vector<uint32_t> list(size_t(kWidth) * kHeight);
  for (uint32_t i = 0; i < list.size(); ++i) list[i] = i;
  return list;
}

struct Tally {
  size_t throughB = 0, throughBNothingBehind = 0, onA = 0, empty = 0;
};

// The answers every listed pixel away from silhouettes must have.
Tally expectRevealed(const RevealScene& s, const RevealReadback& r, const std::vector<uint32_t>& list,
                     const std::string& what) {
  const FrameCamera& camera = r.camera;
  const glm::mat4 worldPreviousA = s.scene.worldMatrixAt(s.a.node, kTime - 1.0f / kFps);
  Tally tally;
  size_t failures = 0;
  auto fail = [&](uint32_t x, uint32_t y, const std::string& message) {
    if (++failures <= 8) ADD_FAILURE() << what << " at " << x << "," << y << ": " << message;
  };
  for (const uint32_t index : list) {
    const uint32_t x = index % kWidth, y = index / kWidth;
    const Coverage onA = coverage(s.scene, camera, s.a, x, y), onB = coverage(s.scene, camera, s.b, x, y);
    if (onA == Coverage::Edge || onB == Coverage::Edge) continue;
    const glm::vec4 color = r.revealed.color[index], nd = r.revealed.normalDepth[index];
    const glm::vec2 velocity = r.revealed.velocity[index];
    const uint32_t id = r.revealed.objectId[index];
    if (onB == Coverage::Inside && onA == Coverage::Inside) {
      ++tally.throughB;
      if (r.raster.objectId[index] != s.b.objectId) fail(x, y, "the raster should see B");
      const QuadHit a = hitQuad(s.scene, camera, s.a, x + 0.5, y + 0.5, kTime);
      if (id != s.a.objectId)
        fail(x, y, "revealed id " + std::to_string(id) + ", A is " + std::to_string(s.a.objectId));
      if (!(std::abs(nd.w - a.depth) <= 1e-4 * a.depth))
        fail(x, y, "revealed depth " + std::to_string(nd.w) + ", A's is " + std::to_string(a.depth));
      if (!(glm::dot(glm::dvec3(glm::vec3(nd)), a.worldNormal) > 1.0 - 1e-5)) fail(x, y, "revealed normal is not A's");
      const glm::dvec3 expected = shadedA(s.scene, a.worldNormal);
      for (int c = 0; c < 3; ++c)
        if (!(std::abs(color[c] - expected[c]) <= 1e-5)) fail(x, y, "revealed colour is not A's shading");
      if (color.a != 1.0f) fail(x, y, "revealed alpha");
      // The same point of A a frame earlier, projected: its motion in pixels per frame.
      const glm::dvec3 previous = glm::dvec3(glm::dmat4(worldPreviousA) * glm::dvec4(a.objectPoint, 1.0));
      const glm::dvec4 clip = glm::dmat4(camera.viewProjPrevious) * glm::dvec4(previous, 1.0);
      const glm::dvec2 motion = glm::dvec2(x + 0.5, y + 0.5) - glm::dvec2((clip.x / clip.w * 0.5 + 0.5) * kWidth,
                                                                          (clip.y / clip.w * 0.5 + 0.5) * kHeight);
      if (!(std::abs(velocity.x - motion.x) <= 2e-3 + 1e-3 * std::abs(motion.x)) ||
          !(std::abs(velocity.y - motion.y) <= 2e-3 + 1e-3 * std::abs(motion.y)))
        fail(x, y,
             "revealed velocity " + std::to_string(velocity.x) + "," + std::to_string(velocity.y) + ", A moves " +
                 std::to_string(motion.x) + "," + std::to_string(motion.y));
      continue;
    }
    // Nothing behind what the raster sees: through B with A beside it, on A, or on nothing.
    if (onB == Coverage::Inside)
      ++tally.throughBNothingBehind;
    else if (onA == Coverage::Inside)
      ++tally.onA;
    else
      ++tally.empty;
    if (id != 0u) fail(x, y, "revealed id " + std::to_string(id) + " where nothing is behind");
    if (nd != glm::vec4(0.0f, 0.0f, 0.0f, camera.zfar)) fail(x, y, "not the far depth where nothing is behind");
    if (velocity != glm::vec2(0.0f)) fail(x, y, "velocity where nothing is behind");
    if (color != glm::vec4(0.0f, 0.0f, 0.0f, 1.0f)) fail(x, y, "not the background colour");
  }
  EXPECT_EQ(failures, 0u) << what;
  return tally;
}

using HybridRevealTest = VulkanTest;

TEST_F(HybridRevealTest, ObjectIdStopFindsThePlaneBehindTheQuad) {
  const RevealScene s = revealScene();
  const std::vector<uint32_t> list = everyPixel();
  HybridSettings settings;
  const RevealReadback r = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, settings);
  const Tally t = expectRevealed(s, r, list, "object-id stop");
  // The scene is what the test means: every case present, B moving on screen.
  EXPECT_GT(t.throughB, 50u);
  EXPECT_GT(t.throughBNothingBehind, 20u);
  EXPECT_GT(t.onA, 200u);
  EXPECT_GT(t.empty, 200u);
  const size_t centre = size_t(kHeight / 2) * kWidth + kWidth / 2;
  EXPECT_EQ(r.raster.objectId[centre], s.b.objectId);
  EXPECT_LT(r.raster.velocity[centre].x, -2.0f);
  // The revealed colour is A's as the raster shades it where A is uncovered.
  size_t compared = 0;
  for (size_t i = 0; i < list.size(); ++i) {
    const uint32_t x = uint32_t(i % kWidth), y = uint32_t(i / kWidth);
    if (coverage(s.scene, r.camera, s.a, x, y) != Coverage::Inside ||
        coverage(s.scene, r.camera, s.b, x, y) != Coverage::Inside)
      continue;
    for (size_t j = 0; j < list.size(); j += 7) {
      if (r.raster.objectId[j] != s.a.objectId) continue;
      EXPECT_LT(mblur::maxAbsDifference(r.revealed.color[i], r.raster.color[j]), 1e-6f) << i << " vs raster " << j;
      ++compared;
      break;
    }
  }
  EXPECT_GT(compared, 50u);
  // One trace per listed pixel.
  EXPECT_EQ(r.counters.rayCount, list.size());
  EXPECT_EQ(r.counters.maskCount, list.size());
}

// The rays start just short of the surface the raster sees (nothing of another object lies
// nearer on the same ray): where B's pixels are told they see A's depth, and no object, the ray
// starts past B and meets A; where nothing lies behind B and they are told a depth past it, the
// ray meets nothing. Started at the eye, both would meet B.
TEST_F(HybridRevealTest, RaysStartAtTheRastersSurface) {
  const RevealScene s = revealScene();
  const std::vector<uint32_t> list = everyPixel();
  FrameCamera camera;
  std::vector<int> expected(list.size(), -1);  // the revealed id where the edit leaves one to expect
  const auto edit = [&](passes::LayerContents& raster) {
    for (const uint32_t index : list) {
      const uint32_t x = index % kWidth, y = index / kWidth;
      if (raster.objectId[index] != s.b.objectId || coverage(s.scene, camera, s.b, x, y) != Coverage::Inside) continue;
      const Coverage onA = coverage(s.scene, camera, s.a, x, y);
      if (onA == Coverage::Edge) continue;
      const QuadHit a = hitQuad(s.scene, camera, s.a, x + 0.5, y + 0.5, kTime);
      raster.objectId[index] = 0u;
      raster.depth[index] = onA == Coverage::Inside ? float(a.depth) : 2.0f * raster.depth[index];
      expected[index] = onA == Coverage::Inside ? int(s.a.objectId) : 0;
    }
  };
  // The camera the edit projects with: the frame's, as a plain reveal reads it back.
  camera = runReveal(context(), s.scene, kTime, kWidth, kHeight, {}, HybridSettings{}).camera;
  const RevealReadback r = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, HybridSettings{}, edit);
  size_t toA = 0, toNothing = 0;
  for (const uint32_t index : list) {
    if (expected[index] < 0) continue;
    EXPECT_EQ(r.revealed.objectId[index], uint32_t(expected[index])) << "pixel " << index;
    (expected[index] == 0 ? toNothing : toA) += 1;
  }
  EXPECT_GT(toA, 50u);
  EXPECT_GT(toNothing, 20u);
}

TEST_F(HybridRevealTest, LuminanceStopGivesTheSameAnswer) {
  const RevealScene s = revealScene();
  const std::vector<uint32_t> list = everyPixel();
  HybridSettings settings;
  settings.stop = RevealStop::Luminance;
  const RevealReadback r = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, settings);
  const Tally t = expectRevealed(s, r, list, "luminance stop");
  EXPECT_GT(t.throughB, 50u);
  // A trace, then one step past the first hit wherever there is one.
  EXPECT_GE(r.counters.rayCount, list.size() + t.throughB + t.throughBNothingBehind + t.onA);
  EXPECT_LE(r.counters.rayCount, 2 * list.size());
  // Equal to the object-id stop wherever the pixel is off every silhouette.
  settings.stop = RevealStop::ObjectId;
  const RevealReadback byId = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, settings);
  size_t compared = 0;
  for (const uint32_t i : list) {
    const uint32_t x = i % kWidth, y = i / kWidth;
    if (coverage(s.scene, r.camera, s.a, x, y) == Coverage::Edge ||
        coverage(s.scene, r.camera, s.b, x, y) == Coverage::Edge)
      continue;
    EXPECT_EQ(r.revealed.objectId[i], byId.revealed.objectId[i]) << x << "," << y;
    EXPECT_NEAR(r.revealed.normalDepth[i].w, byId.revealed.normalDepth[i].w, 1e-6f * byId.revealed.normalDepth[i].w);
    EXPECT_LT(mblur::maxAbsDifference(r.revealed.color[i], byId.revealed.color[i]), 1e-6f) << x << "," << y;
    ++compared;
  }
  EXPECT_GT(compared, list.size() / 2);
}

// With B as bright as A (the same colour, ambient light only) the luminance stop steps past A
// too: after A there is nothing, so the background is revealed; bounded to one step it keeps
// the last hit, A.
TEST_F(HybridRevealTest, LuminanceStopStepsPastSurfacesOfEqualLuminance) {
  RevealScene s = revealScene(kColorA);
  s.scene.light.color = glm::vec3(0.0f);
  HybridSettings settings;
  settings.stop = RevealStop::Luminance;
  std::vector<uint32_t> list;
  {
    const FrameCamera camera = frameCamera(s.scene, kTime, kWidth, kHeight);
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x)
        if (coverage(s.scene, camera, s.a, x, y) == Coverage::Inside &&
            coverage(s.scene, camera, s.b, x, y) == Coverage::Inside)
          list.push_back(y * kWidth + x);
  }
  ASSERT_GT(list.size(), 50u);
  for (const uint32_t steps : {5u, 1u}) {
    settings.maxRecursion = steps;
    const RevealReadback r = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, settings);
    for (const uint32_t i : list) {
      EXPECT_EQ(r.revealed.objectId[i], steps == 1 ? s.a.objectId : 0u) << "max recursion " << steps << " at " << i;
    }
    // B, A, then (with room for it) the trace that finds nothing.
    EXPECT_EQ(r.counters.rayCount, (steps == 1 ? 2u : 3u) * list.size()) << "max recursion " << steps;
  }
}

TEST_F(HybridRevealTest, MovingPlaneRevealsItsOwnVelocity) {
  const RevealScene s = revealScene(kColorB, glm::vec3(12.0f, -6.0f, 4.0f));
  const std::vector<uint32_t> list = everyPixel();
  const RevealReadback r = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, HybridSettings{});
  const Tally t = expectRevealed(s, r, list, "moving plane");
  EXPECT_GT(t.throughB, 50u);
  // A really moves on screen (so the velocities above are not all zero).
  const size_t centre = size_t(kHeight / 2) * kWidth + kWidth / 2;
  ASSERT_EQ(r.revealed.objectId[centre], s.a.objectId);
  EXPECT_GT(glm::length(r.revealed.velocity[centre]), 0.5f);
}

TEST_F(HybridRevealTest, OnlyListedPixelsAreWritten) {
  const RevealScene s = revealScene();
  // The pixels the raster sees B at, and one far corner.
  const RevealReadback all = runReveal(context(), s.scene, kTime, kWidth, kHeight, everyPixel(), HybridSettings{});
  std::vector<uint32_t> list;
  for (uint32_t i = 0; i < all.raster.objectId.size(); ++i)
    if (all.raster.objectId[i] == s.b.objectId) list.push_back(i);
  list.push_back(0);
  ASSERT_GT(list.size(), 100u);
  const RevealReadback r = runReveal(context(), s.scene, kTime, kWidth, kHeight, list, HybridSettings{});
  std::vector<bool> listed(all.raster.objectId.size(), false);
  for (const uint32_t i : list) listed[i] = true;
  size_t written = 0;
  for (size_t i = 0; i < listed.size(); ++i) {
    if (listed[i]) {
      // As the whole-image reveal found it.
      EXPECT_EQ(r.revealed.objectId[i], all.revealed.objectId[i]) << i;
      EXPECT_EQ(r.revealed.normalDepth[i], all.revealed.normalDepth[i]) << i;
      EXPECT_EQ(r.revealed.color[i], all.revealed.color[i]) << i;
      EXPECT_EQ(r.revealed.velocity[i], all.revealed.velocity[i]) << i;
      ++written;
    } else {
      EXPECT_EQ(r.revealed.objectId[i], kSentinelId) << i;
      EXPECT_EQ(r.revealed.normalDepth[i].w, kSentinelDepth) << i;
      EXPECT_EQ(r.revealed.color[i], kSentinelColor) << i;
      EXPECT_EQ(r.revealed.velocity[i], kSentinelVelocity) << i;
    }
  }
  EXPECT_EQ(written, list.size());
  EXPECT_EQ(r.counters.rayCount, list.size());
  // An empty list dispatches nothing and writes nothing.
  const RevealReadback none = runReveal(context(), s.scene, kTime, kWidth, kHeight, {}, HybridSettings{});
  for (size_t i = 0; i < listed.size(); ++i) ASSERT_EQ(none.revealed.objectId[i], kSentinelId) << i;
  EXPECT_EQ(none.counters.rayCount, 0u);
}

// The whole hybrid render: the ray mask marks pixels of B near its leading edge (it moves
// left, onto A), and the revealed layer holds A's colour at the mask pixels whose coverage
// samples leave B (the ones revealed) and nothing (0) elsewhere.
TEST_F(HybridRevealTest, HybridRenderRevealsThePlaneAtMaskPixels) {
  const RevealScene s = revealScene();
  Renderer renderer(context());
  RenderSettings settings;
  settings.method = Method::Hybrid;
  settings.width = kWidth;
  settings.height = kHeight;
  const RenderResult hybrid = renderer.render(s.scene, settings);
  settings.method = Method::Sharp;
  const RenderResult sharp = renderer.render(s.scene, settings);
  const io::ImageLayer* mask = hybrid.image.find("rayMask");
  const io::ImageLayer* revealed = hybrid.image.find("revealed");
  const io::ImageLayer* raster = sharp.image.find("");
  ASSERT_TRUE(mask && revealed && raster);
  ASSERT_TRUE(hybrid.hybrid.has_value());
  const FrameCamera camera = frameCamera(s.scene, kTime, kWidth, kHeight);
  size_t masked = 0, traced = 0, checked = 0;
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) {
      const size_t i = size_t(y) * kWidth + x;
      const glm::vec3 color(revealed->values[i * 3], revealed->values[i * 3 + 1], revealed->values[i * 3 + 2]);
      const glm::vec3 sharpColor(raster->values[i * 4], raster->values[i * 4 + 1], raster->values[i * 4 + 2]);
      if (mask->ids[i] != HMB_MASK_REVEALED) {
        // Outside the mask, or in it with every coverage sample on B (no weight for a reveal).
        EXPECT_EQ(color, glm::vec3(0.0f)) << "untraced pixel " << x << "," << y << " has a revealed colour";
        masked += mask->ids[i] == HMB_MASK_UNREVEALED ? 1u : 0u;
        continue;
      }
      ++masked;
      ++traced;
      if (coverage(s.scene, camera, s.a, x, y) != Coverage::Inside ||
          coverage(s.scene, camera, s.b, x, y) != Coverage::Inside)
        continue;
      const glm::dvec3 expected = shadedA(s.scene, hitQuad(s.scene, camera, s.a, x + 0.5, y + 0.5, kTime).worldNormal);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(color[c], expected[c], 1e-5) << x << "," << y;
      EXPECT_NE(color, sharpColor) << "the raster sees B at " << x << "," << y << ", the reveal must not";
      ++checked;
    }
  EXPECT_EQ(masked, hybrid.hybrid->maskPixels);
  EXPECT_GT(hybrid.hybrid->edgeCandidates, 0u);  // a mask needs edges, and edges are candidates
  EXPECT_EQ(traced, hybrid.hybrid->revealedPixels);
  EXPECT_EQ(hybrid.hybrid->revealRays, traced);  // one trace each with the object-id stop
  EXPECT_GT(checked, 20u);
}

}  // namespace
}  // namespace hmb::test
