// The deform kernel (kernels/deform/deform_vertices.comp, driven by runtime/device_scene/deformed_vertices.h
// through GpuScene) against its C++ twin scene::deformVertex, on random and adversarial inputs:
// joint matrices with non-uniform scale, shear and mirroring (from the inverse bind matrices),
// weights that do not sum to 1, zero weights, 1e-30 weights, 8 influences, negative and large
// morph weights, skin and morph together; at the frame time and at the previous frame. Vertices
// of meshes that do not deform are left as uploaded.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "hmblur/buffer.h"
#include "kernels/shared/scene_layout.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/vulkan/frame_recorder.h"
#include "scenes/deformation.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

constexpr float kTime = 0.3f;

struct Rng {
  std::mt19937 engine{20261202u};
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(engine); }
  uint32_t below(uint32_t n) { return std::uniform_int_distribution<uint32_t>(0, n - 1)(engine); }
  glm::vec3 vec3(float lo, float hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
};

// An affine matrix with shear, scales from 0.01 to 100 and, at `mirror`, a reflection.
glm::mat4 shearedMatrix(Rng& rng, bool mirror) {
  glm::mat4 m(1.0f);
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) m[c][r] = rng.uniform(-1.0f, 1.0f);
  for (int c = 0; c < 3; ++c) m[c] *= std::pow(10.0f, rng.uniform(-2.0f, 2.0f));
  if (mirror) m[0] = -m[0];
  m[3] = glm::vec4(rng.vec3(-5.0f, 5.0f), 1.0f);
  return m;
}

scene::Mesh randomMesh(Rng& rng, uint32_t vertices, uint32_t influences, uint32_t targets, uint32_t joints) {
  scene::Mesh mesh;
  mesh.name = "random";
  for (uint32_t v = 0; v < vertices; ++v) {
    mesh.positions.push_back(rng.vec3(-3.0f, 3.0f));
    mesh.normals.push_back(glm::normalize(rng.vec3(-1.0f, 1.0f) + glm::vec3(0.0f, 0.0f, 0.01f)));
  }
  for (uint32_t t = 0; t + 2 < vertices; t += 3) mesh.indices.insert(mesh.indices.end(), {t, t + 1, t + 2});
  mesh.influences = influences;
  for (uint32_t v = 0; v < vertices && influences > 0; ++v)
    for (uint32_t i = 0; i < influences; ++i) {
      mesh.joints.push_back(rng.below(joints));
      // Unnormalized weights (the kernel blends what it is given), with zeros, 1e-30 beside
      // ordinary weights, and vertices on a single joint.
      const uint32_t kind = rng.below(8);
      const float w = kind == 0 ? 0.0f : kind == 1 ? 1e-30f : rng.uniform(0.0f, 1.5f);
      mesh.weights.push_back(v % 17 == 0 ? (i == 0 ? 1.0f : 0.0f) : (i == 0 && kind <= 1 ? 0.5f : w));
    }
  for (uint32_t k = 0; k < targets; ++k) {
    scene::MorphTarget target;
    for (uint32_t v = 0; v < vertices; ++v) target.positions.push_back(rng.vec3(-0.5f, 0.5f));
    if (k % 2 == 0)
      for (uint32_t v = 0; v < vertices; ++v) target.normals.push_back(rng.vec3(-0.3f, 0.3f));
    mesh.targets.push_back(std::move(target));
  }
  return mesh;
}

// Skinned (8 influences) and morphing; morphing only; skinned (4 influences); rigid.
scene::Scene randomDeformingScene() {
  Rng rng;
  scene::Scene scene;
  scene.materials.push_back({});
  constexpr uint32_t kJoints = 6;
  scene::Skin skin;
  for (uint32_t j = 0; j < kJoints; ++j) {
    scene::Node node;
    node.parent = j == 0 ? -1 : int32_t(j - 1);
    node.local.translation = rng.vec3(-1.0f, 1.0f);
    node.local.rotation = glm::normalize(glm::quat(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), 1.0f));
    node.local.scale = glm::vec3(rng.uniform(0.5f, 2.0f), rng.uniform(0.5f, 2.0f), rng.uniform(0.5f, 2.0f));
    scene.nodes.push_back(node);
    skin.joints.push_back(j);
    skin.inverseBindMatrices.push_back(shearedMatrix(rng, j == 3));
    // Each joint turns about its own axis over time, so the two times differ.
    scene::AnimationChannel spin;
    spin.node = j;
    spin.path = scene::AnimationPath::Rotation;
    spin.times = {0.0f, 1.0f};
    spin.values = {glm::vec4(0, 0, 0, 1), glm::vec4(std::sin(0.3f * (j + 1)), 0, 0, std::cos(0.3f * (j + 1)))};
    scene.channels.push_back(spin);
  }
  scene.skins.push_back(skin);
  const auto root = static_cast<uint32_t>(scene.nodes.size());
  scene.nodes.push_back({});  // the skinned meshes' identity root
  const auto morphNode = static_cast<uint32_t>(scene.nodes.size());
  scene::Node weighted;
  weighted.weights = {0.7f, -0.4f, 1e-30f, 2.5f};
  scene.nodes.push_back(weighted);
  scene::AnimationChannel weights;
  weights.node = morphNode;
  weights.path = scene::AnimationPath::Weights;
  weights.weightCount = 4;
  weights.times = {0.0f, 1.0f};
  weights.weights = {0.0f, 1.0f, -1.0f, 0.0f, 3.0f, 0.0f, 0.5f, 1e-30f};
  scene.channels.push_back(weights);

  scene.meshes.push_back(randomMesh(rng, 700, 8, 3, kJoints));
  scene.meshes.push_back(randomMesh(rng, 500, 0, 4, kJoints));
  scene.meshes.push_back(randomMesh(rng, 400, 4, 0, kJoints));
  scene.meshes.push_back(randomMesh(rng, 300, 0, 0, kJoints));
  scene.instances.push_back({0, root, 1, 0, int32_t(morphNode)});
  scene.instances.push_back({1, morphNode, 2, -1, int32_t(morphNode)});
  scene.instances.push_back({2, root, 3, 0, -1});
  scene.instances.push_back({3, morphNode, 4, -1, -1});
  return scene;
}

// How large the terms of a deformed position are, for a tolerance relative to them.
float magnitude(const scene::Mesh& mesh, uint32_t v, const std::vector<float>& weights,
                const std::vector<glm::mat4>& joints) {
  float morphed = glm::length(mesh.positions[v]);
  for (size_t k = 0; k < weights.size() && k < mesh.targets.size(); ++k)
    morphed += std::abs(weights[k]) * glm::length(mesh.targets[k].positions[v]);
  if (mesh.influences == 0 || joints.empty()) return morphed;
  float sum = 0.0f;
  for (uint32_t i = 0; i < mesh.influences; ++i) {
    const glm::mat4& m = joints[mesh.joints[v * mesh.influences + i]];
    float largest = 0.0f;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(m[c][r]));
    sum += mesh.weights[v * mesh.influences + i] * largest * 4.0f * (morphed + 1.0f);
  }
  return sum;
}

class DeformKernelTest : public VulkanTest {};

TEST_F(DeformKernelTest, EqualsTheHostOnRandomAndAdversarialVertices) {
  const scene::Scene scene = randomDeformingScene();
  GpuScene gpu(context(), scene);
  ASSERT_TRUE(gpu.deforms());
  gpu.setFrame(scene, kTime, 64, 64);
  vk::FrameRecorder frame(context());
  frame.begin();
  gpu.recordFrameDeformation(frame);
  frame.submitAndWait();
  const std::vector<gpu::GpuVertex> current = gpu.vertices().download<gpu::GpuVertex>();
  const std::vector<gpu::GpuVertex> previous = gpu.previousVertices().download<gpu::GpuVertex>();

  const float previousTime = kTime - 1.0f / scene.settings.fps;
  uint32_t base = 0, checked = 0;
  for (const scene::Instance& instance : scene.instances) {
    const scene::Mesh& mesh = scene.meshes[instance.mesh];
    for (const auto& [time, device] : {std::pair{kTime, &current}, std::pair{previousTime, &previous}}) {
      const std::vector<float> weights = scene::morphWeightsAt(scene, instance, time);
      const std::vector<glm::mat4> joints = scene::jointMatricesAt(scene, instance, time);
      for (uint32_t v = 0; v < mesh.positions.size(); ++v) {
        const scene::DeformedVertex expected = scene::deformVertex(mesh, v, weights, joints);
        const gpu::GpuVertex& got = (*device)[base + v];
        const float tolerance = 2e-6f * (1.0f + magnitude(mesh, v, weights, joints));
        ASSERT_LE(glm::length(glm::vec3(got.position) - expected.position), tolerance)
            << "instance " << instance.objectId << " vertex " << v << " at t = " << time;
        ASSERT_EQ(got.position.w, 1.0f);
        ASSERT_GE(glm::dot(glm::vec3(got.normal), expected.normal), 1.0f - 1e-4f)
            << "instance " << instance.objectId << " vertex " << v << " at t = " << time;
        if (!instance.deforms()) {
          ASSERT_EQ(glm::vec3(got.position), mesh.positions[v]);  // never written
          ASSERT_EQ(glm::vec3(got.normal), mesh.normals[v]);
        }
        ++checked;
      }
    }
    base += static_cast<uint32_t>(mesh.positions.size());
  }
  EXPECT_EQ(checked, 2u * (700 + 500 + 400 + 300));
  // The two times differ: the kernel did not write one slot twice.
  EXPECT_NE(current[0].position, previous[0].position);
}

// The curved path's vertex kernel (raster/transform_shutter_path.comp) on the same scene: a
// deformed vertex at mid-shutter and shutter open lies on the line from its frame position to
// its previous-frame one (past it when the shutter is longer than a frame), a rigid one at its
// mesh position, each through its instance's clip transforms at those times.
TEST_F(DeformKernelTest, ShutterPathPositionsFollowTheDeformationBetweenItsTwoTimes) {
  scene::Scene scene = randomDeformingScene();
  scene.settings.exposure = 1.5f / scene.settings.fps;
  GpuScene gpu(context(), scene);
  gpu.setFrame(scene, kTime, 64, 64);
  passes::GBufferStage stage(context(), passes::defaultVisibilityScheme(context()));
  const std::vector<gpu::GpuShutterClip> clips = shutterClips(scene, kTime, scene.settings.exposure, 64, 64);
  stage.prepare(gpu, 64, 64, passes::GBufferStage::ShutterPaths{scene.settings.exposure, scene.settings.fps, clips});
  vk::FrameRecorder frame(context());
  passes::submitUntilRasterFits(frame, stage.rasterizer(), [&](vk::FrameRecorder& f) { stage.record(f, gpu); });
  const std::vector<gpu::GpuVertex> current = gpu.vertices().download<gpu::GpuVertex>();
  const std::vector<gpu::GpuVertex> previous = gpu.previousVertices().download<gpu::GpuVertex>();
  const std::vector<gpu::GpuInstanceVertex> instanceVertices = gpu.instanceVertices().download<gpu::GpuInstanceVertex>();
  const std::vector<glm::vec4> mid = stage.clipMid().download<glm::vec4>(), open = stage.clipOpen().download<glm::vec4>();
  const float openFrames = scene.settings.exposure * scene.settings.fps;
  uint32_t deformed = 0;
  for (uint32_t i = 0; i < gpu.instanceVertexCount(); ++i) {
    const gpu::GpuInstanceVertex iv = instanceVertices[i];
    const bool deforms = scene.instances[iv.instance].deforms();
    const glm::vec4 p = current[iv.meshVertex].position, q = previous[iv.meshVertex].position;
    const glm::vec4 atMid = deforms ? glm::mix(p, q, 0.5f * openFrames) : p;
    const glm::vec4 atOpen = deforms ? glm::mix(p, q, openFrames) : p;
    const glm::vec4 expectedMid = clips[iv.instance].clipMid * atMid, expectedOpen = clips[iv.instance].clipOpen * atOpen;
    const float scale = 1.0f + glm::length(expectedMid) + glm::length(expectedOpen);
    ASSERT_LE(glm::length(mid[i] - expectedMid), 1e-5f * scale) << "vertex " << i;
    ASSERT_LE(glm::length(open[i] - expectedOpen), 1e-5f * scale) << "vertex " << i;
    deformed += deforms && p != q;
  }
  EXPECT_GT(deformed, 1000u);
}

// The host twin's own promises: identity joints and zero weights give the rest vertex back;
// a half-and-half blend of two translations lands halfway; a mirroring joint keeps the normal
// on the surface's side; a vanishing normal falls back to the rest one.
TEST(DeformVertexTest, KeepsWhatGltfPromises) {
  scene::Mesh mesh;
  mesh.positions = {glm::vec3(1.0f, 2.0f, 3.0f)};
  mesh.normals = {glm::vec3(0.0f, 0.0f, 1.0f)};
  mesh.influences = 4;
  mesh.joints = {0, 1, 0, 0};
  mesh.weights = {0.5f, 0.5f, 0.0f, 0.0f};
  mesh.targets = {{{glm::vec3(1.0f, 0.0f, 0.0f)}, {glm::vec3(0.0f, 0.0f, -1.0f)}}};
  const glm::mat4 identity(1.0f);
  const std::vector<glm::mat4> same = {identity, identity};
  const scene::DeformedVertex rest = scene::deformVertex(mesh, 0, std::vector<float>{0.0f}, same);
  EXPECT_EQ(rest.position, mesh.positions[0]);
  EXPECT_EQ(rest.normal, mesh.normals[0]);

  glm::mat4 left(1.0f), right(1.0f);
  left[3] = glm::vec4(-2.0f, 0.0f, 0.0f, 1.0f);
  right[3] = glm::vec4(4.0f, 0.0f, 0.0f, 1.0f);
  const std::vector<glm::mat4> apart = {left, right};
  EXPECT_EQ(scene::deformVertex(mesh, 0, std::vector<float>{0.0f}, apart).position, glm::vec3(2.0f, 2.0f, 3.0f));
  // Morph first, then skin: the target's +1 in x is carried along by the blend.
  EXPECT_EQ(scene::deformVertex(mesh, 0, std::vector<float>{1.0f}, apart).position, glm::vec3(3.0f, 2.0f, 3.0f));
  // The target's normal displacement cancels the rest normal: the rest normal is kept.
  EXPECT_EQ(scene::deformVertex(mesh, 0, std::vector<float>{1.0f}, same).normal, mesh.normals[0]);

  glm::mat4 mirror(1.0f);
  mirror[2][2] = -1.0f;  // z mirrored: a surface facing +z now faces -z
  const std::vector<glm::mat4> mirrored = {mirror, mirror};
  EXPECT_EQ(scene::deformVertex(mesh, 0, std::vector<float>{0.0f}, mirrored).normal, glm::vec3(0.0f, 0.0f, -1.0f));
  glm::mat4 sheared(1.0f);
  sheared[0][1] = 1.0f;  // y += x: the plane y = 0 becomes the plane y = x
  mesh.normals[0] = glm::vec3(0.0f, 1.0f, 0.0f);
  const glm::vec3 n = scene::deformVertex(mesh, 0, std::vector<float>{0.0f}, std::vector<glm::mat4>{sheared, sheared}).normal;
  // Perpendicular to the sheared tangents (1, 1, 0) and (0, 0, 1): (-1, 1, 0) / sqrt(2), where
  // carrying the normal by the matrix itself would give (0, 1, 0).
  EXPECT_NEAR(n.x, -std::sqrt(0.5f), 1e-6f);
  EXPECT_NEAR(n.y, std::sqrt(0.5f), 1e-6f);
}

}  // namespace
}  // namespace hmb::test
