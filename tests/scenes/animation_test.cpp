// Animation sampling and the node hierarchy against hand-computed transforms.
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <gtest/gtest.h>

#include "hmblur/scene.h"

namespace hmb::scene {
namespace {

constexpr float kEps = 1e-5f;

void expectVec3(const glm::vec3& actual, const glm::vec3& expected, float eps = kEps) {
  EXPECT_NEAR(actual.x, expected.x, eps);
  EXPECT_NEAR(actual.y, expected.y, eps);
  EXPECT_NEAR(actual.z, expected.z, eps);
}

// Rotations q and -q are the same: compare what they do to the axes.
void expectSameRotation(const glm::quat& actual, const glm::quat& expected, float eps = 1e-4f) {
  for (const glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)})
    expectVec3(actual * axis, expected * axis, eps);
}

glm::vec4 xyzw(const glm::quat& q) { return glm::vec4(q.x, q.y, q.z, q.w); }

Scene oneNode() {
  Scene scene;
  scene.nodes.push_back(Node{"n", -1, Trs{}});
  return scene;
}

AnimationChannel channel(AnimationPath path, Interpolation interpolation, std::vector<float> times,
                         std::vector<glm::vec4> values, uint32_t node = 0) {
  AnimationChannel ch;
  ch.node = node;
  ch.path = path;
  ch.interpolation = interpolation;
  ch.times = std::move(times);
  ch.values = std::move(values);
  return ch;
}

TEST(TrsTest, MatrixAppliesScaleThenRotationThenTranslation) {
  Trs trs;
  trs.translation = {1, 2, 3};
  trs.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 0, 1));
  trs.scale = {2, 1, 1};
  // (1,0,0) -> scaled (2,0,0) -> rotated 90 deg about z (0,2,0) -> translated (1,4,3).
  expectVec3(glm::vec3(trs.matrix() * glm::vec4(1, 0, 0, 1)), {1, 4, 3});
}

TEST(TrsTest, LookRotationPointsMinusZAlongForwardWithYUp) {
  for (const glm::vec3 forward : {glm::vec3(1, 0, 0), glm::vec3(0.3f, -0.5f, -2.0f), glm::vec3(0, -1, 0)}) {
    const glm::quat q = lookRotation(forward);
    expectVec3(q * glm::vec3(0, 0, -1), glm::normalize(forward), 1e-5f);
    // The camera's right axis stays horizontal: no roll.
    EXPECT_NEAR((q * glm::vec3(1, 0, 0)).y, 0.0f, 1e-5f);
  }
}

TEST(AnimationTest, LinearTranslationInterpolatesAndClamps) {
  Scene scene = oneNode();
  scene.nodes[0].local.translation = {9, 9, 9};
  scene.channels.push_back(
      channel(AnimationPath::Translation, Interpolation::Linear, {1.0f, 3.0f}, {{0, 0, 0, 0}, {4, -2, 8, 0}}));
  expectVec3(scene.localTrsAt(0, 2.0f).translation, {2, -1, 4});
  expectVec3(scene.localTrsAt(0, 1.5f).translation, {1, -0.5f, 2});
  expectVec3(scene.localTrsAt(0, 1.0f).translation, {0, 0, 0});
  expectVec3(scene.localTrsAt(0, -5.0f).translation, {0, 0, 0});   // before the first key
  expectVec3(scene.localTrsAt(0, 10.0f).translation, {4, -2, 8});  // after the last key
  // Only the animated path is overridden.
  expectVec3(scene.localTrsAt(0, 2.0f).scale, {1, 1, 1});
}

TEST(AnimationTest, StepHoldsThePreviousKey) {
  Scene scene = oneNode();
  scene.channels.push_back(channel(AnimationPath::Scale, Interpolation::Step, {0.0f, 1.0f, 2.0f},
                                   {{1, 1, 1, 0}, {2, 2, 2, 0}, {3, 3, 3, 0}}));
  expectVec3(scene.localTrsAt(0, 0.99f).scale, {1, 1, 1});
  expectVec3(scene.localTrsAt(0, 1.0f).scale, {2, 2, 2});
  expectVec3(scene.localTrsAt(0, 1.5f).scale, {2, 2, 2});
  expectVec3(scene.localTrsAt(0, 7.0f).scale, {3, 3, 3});
}

TEST(AnimationTest, CubicSplineFollowsTheHermiteFormulaWithScaledTangents) {
  Scene scene = oneNode();
  // Keys at t = 0 and t = 2: value 0 with out-tangent 1, value 4 with in-tangent 2.
  scene.channels.push_back(channel(AnimationPath::Translation, Interpolation::CubicSpline, {0.0f, 2.0f},
                                   {{9, 0, 0, 0},
                                    {0, 0, 0, 0},
                                    {1, 0, 0, 0},  // key 0: in, value, out
                                    {2, 0, 0, 0},
                                    {4, 0, 0, 0},
                                    {9, 0, 0, 0}}));  // key 1
  // u = 0.5, dt = 2: h00 = 0.5, h10 = 0.125, h01 = 0.5, h11 = -0.125
  // p = 0.5*0 + 0.125*2*1 + 0.5*4 - 0.125*2*2 = 1.75
  EXPECT_NEAR(scene.localTrsAt(0, 1.0f).translation.x, 1.75f, kEps);
  // u = 0.25: h00 = 0.84375, h10 = 0.140625, h01 = 0.15625, h11 = -0.046875
  // p = 0.140625*2*1 + 0.15625*4 - 0.046875*2*2 = 0.71875
  EXPECT_NEAR(scene.localTrsAt(0, 0.5f).translation.x, 0.71875f, kEps);
  // At and beyond the keys: the values, never the tangents.
  EXPECT_NEAR(scene.localTrsAt(0, 0.0f).translation.x, 0.0f, kEps);
  EXPECT_NEAR(scene.localTrsAt(0, 3.0f).translation.x, 4.0f, kEps);
}

TEST(AnimationTest, LinearRotationIsSlerp) {
  Scene scene = oneNode();
  const glm::vec3 y(0, 1, 0);
  scene.channels.push_back(channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f},
                                   {xyzw(glm::angleAxis(0.0f, y)), xyzw(glm::angleAxis(2.0f, y))}));
  // Constant angular speed: a quarter of the way is a quarter of the angle (nlerp would not be).
  expectSameRotation(scene.localTrsAt(0, 0.25f).rotation, glm::angleAxis(0.5f, y));
  expectSameRotation(scene.localTrsAt(0, 0.5f).rotation, glm::angleAxis(1.0f, y));
  EXPECT_NEAR(glm::length(scene.localTrsAt(0, 0.3f).rotation), 1.0f, kEps);
}

TEST(AnimationTest, RotationTakesTheShortestPath) {
  Scene scene = oneNode();
  const glm::vec3 z(0, 0, 1);
  // The second key is stored negated (same rotation, opposite hemisphere): still 45 deg midway.
  scene.channels.push_back(channel(AnimationPath::Rotation, Interpolation::Linear, {0.0f, 1.0f},
                                   {xyzw(glm::angleAxis(0.0f, z)), -xyzw(glm::angleAxis(glm::half_pi<float>(), z))}));
  expectSameRotation(scene.localTrsAt(0, 0.5f).rotation, glm::angleAxis(glm::quarter_pi<float>(), z));
}

TEST(AnimationTest, CubicRotationIsNormalized) {
  Scene scene = oneNode();
  const glm::vec4 a = xyzw(glm::angleAxis(0.0f, glm::vec3(1, 0, 0)));
  const glm::vec4 b = xyzw(glm::angleAxis(1.5f, glm::vec3(1, 0, 0)));
  const glm::vec4 zero(0.0f);
  scene.channels.push_back(
      channel(AnimationPath::Rotation, Interpolation::CubicSpline, {0.0f, 1.0f}, {zero, a, zero, zero, b, zero}));
  const glm::quat mid = scene.localTrsAt(0, 0.5f).rotation;
  EXPECT_NEAR(glm::length(mid), 1.0f, kEps);
  // Zero tangents, symmetric: halfway is the normalized average, i.e. 0.75 rad about x.
  expectSameRotation(mid, glm::angleAxis(0.75f, glm::vec3(1, 0, 0)));
}

TEST(AnimationTest, ChannelsOfOtherNodesDoNotApply) {
  Scene scene = oneNode();
  scene.nodes.push_back(Node{"other", -1, Trs{}});
  scene.channels.push_back(
      channel(AnimationPath::Translation, Interpolation::Linear, {0.0f, 1.0f}, {{0, 0, 0, 0}, {1, 1, 1, 0}}, 1));
  expectVec3(scene.localTrsAt(0, 0.5f).translation, {0, 0, 0});
  expectVec3(scene.localTrsAt(1, 0.5f).translation, {0.5f, 0.5f, 0.5f});
  EXPECT_FALSE(scene.isAnimated(0));
  EXPECT_TRUE(scene.isAnimated(1));
}

TEST(AnimationTest, MalformedChannelIsIgnoredNotFatal) {
  Scene scene = oneNode();
  scene.channels.push_back(
      channel(AnimationPath::Translation, Interpolation::CubicSpline, {0.0f, 1.0f}, {{1, 1, 1, 0}}));  // too few values
  scene.channels.push_back(channel(AnimationPath::Translation, Interpolation::Linear, {}, {}));
  expectVec3(scene.localTrsAt(0, 0.5f).translation, {0, 0, 0});
  expectVec3(scene.localTrsAt(42, 0.5f).translation, {0, 0, 0});  // node out of range
}

TEST(HierarchyTest, WorldMatrixComposesParentsFirst) {
  Scene scene;
  Trs parent;
  parent.translation = {1, 0, 0};
  parent.rotation = glm::angleAxis(glm::half_pi<float>(), glm::vec3(0, 1, 0));
  Trs child;
  child.translation = {0, 0, 1};
  child.scale = {2, 2, 2};
  scene.nodes.push_back(Node{"parent", -1, parent});
  scene.nodes.push_back(Node{"child", 0, child});
  // Rotating (0,0,1) by 90 deg about y gives (1,0,0); plus the parent's (1,0,0).
  expectVec3(glm::vec3(scene.worldMatrixAt(1, 0.0f)[3]), {2, 0, 0});
  // A child-space point (0,0,1) -> scaled (0,0,2) -> +(0,0,1) = (0,0,3) -> rotated (3,0,0) -> (4,0,0).
  expectVec3(glm::vec3(scene.worldMatrixAt(1, 0.0f) * glm::vec4(0, 0, 1, 1)), {4, 0, 0});

  // Animating the parent moves the child.
  scene.channels.push_back(
      channel(AnimationPath::Translation, Interpolation::Linear, {0.0f, 1.0f}, {{1, 0, 0, 0}, {1, 10, 0, 0}}, 0));
  expectVec3(glm::vec3(scene.worldMatrixAt(1, 0.5f)[3]), {2, 5, 0});
  EXPECT_TRUE(scene.isAnimated(1));
  EXPECT_TRUE(scene.isAnimated(0));
}

TEST(HierarchyTest, CycleDoesNotHang) {
  Scene scene;
  scene.nodes.push_back(Node{"a", 1, Trs{}});
  scene.nodes.push_back(Node{"b", 0, Trs{}});
  scene.nodes[0].local.translation = {1, 0, 0};
  const glm::mat4 m = scene.worldMatrixAt(0, 0.0f);  // terminates
  EXPECT_TRUE(std::isfinite(m[3][0]));
  EXPECT_FALSE(scene.isAnimated(0));
}

TEST(SceneTest, BoundsAndTriangleCountFollowInstances) {
  Scene scene;
  Mesh tri;
  tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  tri.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  tri.indices = {0, 1, 2};
  scene.meshes.push_back(tri);
  Trs a, b;
  a.translation = {10, 0, 0};
  b.translation = {-5, 0, 0};
  scene.nodes.push_back(Node{"a", -1, a});
  scene.nodes.push_back(Node{"b", -1, b});
  scene.instances.push_back(Instance{0, 0, 1});
  scene.instances.push_back(Instance{0, 1, 2});
  EXPECT_EQ(scene.triangleCount(), 2u);
  scene.channels.push_back(
      channel(AnimationPath::Translation, Interpolation::Linear, {0.0f, 1.0f}, {{10, 0, 0, 0}, {10, 0, 4, 0}}, 0));
  const Aabb bounds = scene.boundsAt(1.0f);
  expectVec3(bounds.min, {-5, 0, 0});
  expectVec3(bounds.max, {11, 1, 4});
  EXPECT_TRUE(Scene{}.boundsAt(0.0f).empty());
}

}  // namespace
}  // namespace hmb::scene
