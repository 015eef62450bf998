// Correctness oracle for the compute rasterizer: the same clip-space triangles drawn by a
// classic Vulkan graphics pipeline (render pass, vertex + fragment shader, depth test) on the
// same device. Tests and benchmarks only.
//
// Conventions the compute rasterizer must match to compare exactly:
// - Viewport: the whole image, minDepth 0, maxDepth 1. Framebuffer x = (x/w + 1) * width / 2,
//   y = (y/w + 1) * height / 2 with y pointing DOWN (row 0 is the top row of the image).
// - Samples: one per pixel, at the pixel centre (px + 0.5, py + 0.5). Vertex positions are
//   snapped to the device's sub-pixel grid (subPixelPrecisionBits, 8 on lavapipe).
// - Ties: a centre exactly on an edge is covered only when the edge is a top or left edge
//   (the top-left rule in y-down framebuffer space). Vulkan itself only promises that one of
//   two triangles sharing that edge covers the centre; the tests check that the device uses
//   the top-left rule (lavapipe does).
// - Depth: z/w interpolated linearly in screen space (no perspective correction), clipped
//   to 0 <= z/w <= 1 (depth clamp off); GREATER test (depth is reversed: nearer is larger),
//   so on equal depth the triangle that comes first in the span wins. Callers that want "smallest id wins" pass triangles sorted by id.
// - Facing: with framebuffer (y-down) positions p0, p1, p2 and
//     cross = (p1.x - p0.x) * (p2.y - p0.y) - (p1.y - p0.y) * (p2.x - p0.x),
//   a triangle is FRONT-facing when cross < 0: counter-clockwise as the image is viewed
//   (row 0 at the top), i.e. counter-clockwise in a y-UP framebuffer frame. That is glTF's
//   counter-clockwise front face after a projection that flips y for Vulkan, and Vulkan's
//   VK_FRONT_FACE_COUNTER_CLOCKWISE. Zero-area triangles draw nothing.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <vulkan/vulkan.h>

#include "hmblur/buffer.h"
#include "kernels/shared/scene_layout.h"
#include "tests/oracle/oracle_vulkan.h"

namespace hmb::vk {
class Context;
}

namespace hmb::oracle {

struct OracleTriangle {
  glm::vec4 clip[3];  // clip-space positions (x right, y down in NDC, depth z/w in [0, 1], 1 nearest)
  uint32_t id = 0;    // written to the id image as id + 1 (0 = no triangle)
  bool doubleSided = false;  // false: back faces are culled
};

struct OracleImage {
  uint32_t width = 0, height = 0;
  std::vector<uint32_t> ids;  // row-major, row 0 at the top; id + 1 of the visible triangle, 0 = none
  std::vector<float> depth;   // z/w of the visible triangle, 0.0 (the far plane) where empty

  uint32_t idAt(uint32_t x, uint32_t y) const { return ids[size_t(y) * width + x]; }
  float depthAt(uint32_t x, uint32_t y) const { return depth[size_t(y) * width + x]; }
};

// Keeps pipelines, render pass, attachments and buffers alive between calls, so benchmarks
// time only the draw. Throws hmb::Error when the context's queue cannot do graphics.
class GraphicsRasterizer {
 public:
  GraphicsRasterizer(const vk::Context& context, uint32_t width, uint32_t height);
  ~GraphicsRasterizer();
  GraphicsRasterizer(const GraphicsRasterizer&) = delete;
  GraphicsRasterizer& operator=(const GraphicsRasterizer&) = delete;

  OracleImage rasterize(std::span<const OracleTriangle> triangles);

  // GPU time of the last render pass (clear, draws, store), from timestamp queries; the
  // vertex upload and the readback copies are outside. Empty without timestamp support.
  std::optional<double> lastDrawMilliseconds() const { return lastDrawMs_; }

  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  VkFormat depthFormat() const { return depthFormat_; }

 private:
  void createRenderPass();
  void createAttachments();
  void createPipelines();
  void* reserveVertices(VkDeviceSize bytes);  // where the host writes this call's vertices
  void release();

  const vk::Context& context_;
  uint32_t width_, height_;
  DrawTimer timer_;
  VkFormat depthFormat_ = VK_FORMAT_UNDEFINED;
  VkRenderPass renderPass_ = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayout_ = VK_NULL_HANDLE;
  VkPipeline pipelines_[2] = {VK_NULL_HANDLE, VK_NULL_HANDLE};  // [0] culls back faces, [1] culls none
  Attachment color_, depth_;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  vk::Buffer vertices_, staging_;  // staging_ only where vertex memory is not host-visible
  vk::Buffer idsReadback_, depthReadback_;
  std::optional<double> lastDrawMs_;
};

// One-shot form: builds a GraphicsRasterizer, draws, reads back.
OracleImage rasterizeWithGraphicsPipeline(const vk::Context& context, uint32_t width, uint32_t height,
                                          std::span<const OracleTriangle> triangles);

// Scene triangles (GpuTriangle indices into `clip`, the clip-space vertices) as oracle
// triangles with id = position in the list, so that on equal depth the smallest id wins as in
// the compute visibility buffer. doubleSided is per instance (GpuTriangle::instance indexes it).
std::vector<OracleTriangle> oracleTriangles(std::span<const glm::vec4> clip,
                                            std::span<const gpu::GpuTriangle> triangles,
                                            const std::vector<bool>& doubleSided);

// Fraction of pixels where a compute visibility buffer (entries (triangle id, depth key),
// HMB_VIS_EMPTY when empty) and the oracle see the same triangle, or both none. Throws
// hmb::Error when the buffer has fewer entries than the image has pixels.
double idAgreement(std::span<const glm::uvec2> visibility, const OracleImage& oracle);

}  // namespace hmb::oracle
