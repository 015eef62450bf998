#include <gtest/gtest.h>

#include "hmblur/load_scene.h"
#include "runtime/device_scene/gpu_scene.h"
#include "tests/support/vulkan_test.h"

namespace hmb::test {
namespace {

using GpuSceneTest = VulkanTest;

TEST_F(GpuSceneTest, UploadExpandsInstancesAndWritesTheFrame) {
  const scene::Scene scene = scene::loadScene("living-room");
  GpuScene gpu(context(), scene);
  EXPECT_EQ(gpu.triangleCount(), scene.triangleCount());
  uint32_t vertices = 0;
  for (const scene::Instance& instance : scene.instances) vertices += scene.meshes[instance.mesh].positions.size();
  EXPECT_EQ(gpu.instanceVertexCount(), vertices);

  gpu.setFrame(scene, scene.settings.frameTime, 64, 36);
  const auto triangles = gpu.triangles().download<gpu::GpuTriangle>();
  for (const gpu::GpuTriangle& t : triangles) {
    ASSERT_LT(t.v0, vertices);
    ASSERT_LT(t.v1, vertices);
    ASSERT_LT(t.v2, vertices);
    ASSERT_LT(t.instance, scene.instances.size());
  }
  const auto instances = gpu.instances().download<gpu::GpuInstance>();
  ASSERT_EQ(instances.size(), scene.instances.size());
  for (size_t i = 0; i < instances.size(); ++i) EXPECT_EQ(instances[i].objectId, scene.instances[i].objectId);
}

TEST_F(GpuSceneTest, CameraLooksDownMinusZWithYDownClipSpace) {
  scene::Scene scene;  // no camera node: identity camera at the origin
  scene.camera = scene::Camera{};
  scene.camera->znear = 0.1f;
  scene.camera->zfar = 100.0f;
  const FrameCamera camera = frameCamera(scene, 0.0f, 100, 100);
  const glm::vec4 ahead = camera.viewProjCurrent * glm::vec4(0.0f, 0.0f, -10.0f, 1.0f);
  EXPECT_NEAR(ahead.x / ahead.w, 0.0f, 1e-6f);
  EXPECT_GT(ahead.z / ahead.w, 0.0f);
  EXPECT_LT(ahead.z / ahead.w, 1.0f);
  const glm::vec4 up = camera.viewProjCurrent * glm::vec4(0.0f, 1.0f, -10.0f, 1.0f);
  EXPECT_LT(up.y / up.w, 0.0f) << "world up must map to the top of the image (negative clip y)";
}

}  // namespace
}  // namespace hmb::test
