// The G-buffer oracle: the whole compute G-buffer (visibility and resolve) done by the device's
// graphics pipeline for the same frame. The transform kernel's clip-space vertices at t and
// t - 1/fps are drawn in triangle-id order (reversed depth, GREATER test, one pipeline per
// sidedness as graphics_raster.h does), and each fragment computes what resolve_gbuffer computes
// at a pixel centre, from the rasterizer's perspective-correct attributes: the same shading
// function, packed into the same two records (kernels/shared/layer_layout.h). Tests and
// benchmarks only.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "hmblur/buffer.h"
#include "kernels/shared/scene_layout.h"
#include "tests/oracle/oracle_vulkan.h"

namespace hmb {
class GpuScene;
}

namespace hmb::oracle {

class GraphicsGBuffer {
 public:
  // scene: the scene's buffers on `context` (a GpuScene made there, set to the frame);
  // clipCurrent, clipPrevious, shading: the transform kernel's output for that frame, one per
  // instance vertex. Throws hmb::Error when the context's queue cannot draw.
  GraphicsGBuffer(const vk::Context& context, const GpuScene& scene, std::span<const glm::vec4> clipCurrent,
                  std::span<const glm::vec4> clipPrevious, std::span<const gpu::GpuVertexShading> shading,
                  uint32_t width, uint32_t height);
  ~GraphicsGBuffer();
  GraphicsGBuffer(const GraphicsGBuffer&) = delete;
  GraphicsGBuffer& operator=(const GraphicsGBuffer&) = delete;

  // The layer's two records per pixel, row 0 at the top (the background where nothing is drawn).
  struct Image {
    std::vector<glm::uvec4> samples, surfaces;
  };
  // Draws the frame and reads it back.
  Image render();
  // Device time of the last render pass (clears, draws, stores); empty without timestamps.
  std::optional<double> lastDrawMilliseconds() const { return lastDrawMs_; }

 private:
  void createRenderPass();
  void createFramebuffer();
  void createDescriptors(const GpuScene& scene);
  void createPipelines(bool texturePath);
  void release();

  const vk::Context& context_;
  uint32_t width_, height_;
  DrawTimer timer_;
  VkFormat depthFormat_ = VK_FORMAT_UNDEFINED;
  glm::uvec4 backgroundSample_{0u}, backgroundSurface_{0u};
  std::vector<DrawSpan> draws_;
  vk::Buffer triangles_, clipCurrent_, clipPrevious_, shading_;
  vk::Buffer samplesReadback_, surfacesReadback_;
  Attachment samples_, surfaces_, depth_;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet set_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkPipeline pipelines_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // [0] culls back faces, [1] culls none
  std::optional<double> lastDrawMs_;
};

// How a compute G-buffer (the layer's samples and surfaces) agrees with the oracle's image.
struct GBufferAgreement {
  double objectIds = 1.0;  // share of pixels with the same object id (0: the background)
  // Share of the pixels on the same object where every attribute is within its tolerance below.
  double attributes = 1.0;
  // The largest differences over the pixels on the same object.
  double depthRelative = 0.0;  // |a - b| / max(|a|, |b|)
  double color = 0.0;          // largest channel difference
  double velocityPixels = 0.0;
  double normalRadians = 0.0;
};
// Tolerances: the two interpolate the same attributes with different rounding.
constexpr double kDepthTolerance = 1e-5, kColorTolerance = 1e-3, kVelocityTolerance = 1e-2, kNormalTolerance = 1e-3;
GBufferAgreement compareGBuffers(std::span<const glm::uvec4> samples, std::span<const glm::uvec4> surfaces,
                                 const GraphicsGBuffer::Image& oracle);

}  // namespace hmb::oracle
