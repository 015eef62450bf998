// The G-buffer oracle against the compute G-buffer on the reference scenes: the same objects at
// the same pixels, and the same depth, normal, velocity and shaded colour there, to rounding.
// (The compute rasterizer and the graphics pipeline break ties on shared edges the same way, so
// object ids differ only where rounding moves a silhouette by a pixel centre.)
#include "tests/oracle/graphics_gbuffer.h"

#include <iostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hmblur/load_scene.h"
#include "runtime/device_scene/gpu_scene.h"
#include "runtime/passes/gbuffer_stage.h"
#include "runtime/passes/rasterize_pass.h"
#include "runtime/vulkan/frame_recorder.h"
#include "tests/support/vulkan_test.h"

namespace hmb::oracle {
namespace {

class GraphicsGBufferTest : public test::VulkanTest {};

TEST_F(GraphicsGBufferTest, AgreesWithTheComputeGBufferOnTheReferenceScenes) {
  constexpr uint32_t kWidth = 160, kHeight = 90;
  for (const std::string name : {"living-room", "temple", "bistro"}) {
    SCOPED_TRACE(name);
    const scene::Scene scene = scene::loadScene(name);
    GpuScene gpuScene(context(), scene);
    gpuScene.setFrame(scene, scene.settings.frameTime, kWidth, kHeight);
    passes::GBufferStage stage(context(), passes::defaultVisibilityScheme(context()));
    stage.prepare(gpuScene, kWidth, kHeight);
    vk::FrameRecorder frame(context());
    passes::submitUntilRasterFits(frame, stage.rasterizer(), [&](vk::FrameRecorder& f) { stage.record(f, gpuScene); });

    const size_t vertices = gpuScene.instanceVertexCount();
    std::vector<glm::vec4> clipCurrent = stage.clipCurrent().download<glm::vec4>();
    std::vector<glm::vec4> clipPrevious = stage.clipPrevious().download<glm::vec4>();
    std::vector<gpu::GpuVertexShading> shading = stage.vertexShading().download<gpu::GpuVertexShading>();
    clipCurrent.resize(vertices);
    clipPrevious.resize(vertices);
    shading.resize(vertices);
    GraphicsGBuffer oracle(context(), gpuScene, clipCurrent, clipPrevious, shading, kWidth, kHeight);
    const GraphicsGBuffer::Image image = oracle.render();
    const GBufferAgreement a = compareGBuffers(stage.layer().samples().download<glm::uvec4>(),
                                               stage.layer().surfaces().download<glm::uvec4>(), image);
    std::cout << "[ G-buffer  ] " << name << ": object ids " << 100.0 * a.objectIds << "%, attributes "
              << 100.0 * a.attributes << "%; worst depth " << a.depthRelative << " relative, colour " << a.color
              << ", velocity " << a.velocityPixels << " px, normal " << a.normalRadians << " rad\n";
    EXPECT_GE(a.objectIds, 0.995);
    EXPECT_GE(a.attributes, 0.99);
  }
}

}  // namespace
}  // namespace hmb::oracle
