#include "tests/oracle/graphics_raster.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "hmblur/context.h"
#include "hmblur/error.h"
#include "kernels/raster/raster_layout.h"
#include "oracle_frag.spv.h"
#include "oracle_vert.spv.h"
#include "runtime/vulkan/check.h"

namespace hmb::oracle {
namespace {

// One vertex as the vertex shader reads it; the id is repeated on all three vertices so that
// the flat id does not depend on the provoking-vertex convention.
struct Vertex {
  float clip[4];
  uint32_t id;
};
static_assert(sizeof(Vertex) == 20);

constexpr VkFormat kIdFormat = VK_FORMAT_R32_UINT;

}  // namespace

GraphicsRasterizer::GraphicsRasterizer(const vk::Context& context, uint32_t width, uint32_t height)
    : context_(context), width_(width), height_(height), timer_(context) {
  if (width == 0 || height == 0) throw Error("graphics oracle: image size must be at least 1x1");
  const VkPhysicalDeviceLimits& limits = context.limits();
  if (width > limits.maxFramebufferWidth || height > limits.maxFramebufferHeight)
    throw Error("graphics oracle: " + std::to_string(width) + "x" + std::to_string(height) +
                " exceeds the device's framebuffer limit");

  requireGraphicsQueue(context, "graphics oracle");
  depthFormat_ = pickDepthFormat(context, "graphics oracle");

  try {
    createRenderPass();
    createAttachments();
    createPipelines();
    const VkDeviceSize pixels = VkDeviceSize(width) * height;
    idsReadback_ = vk::Buffer(context, pixels * 4, vk::MemoryUse::Readback, "oracle ids (readback)");
    depthReadback_ = vk::Buffer(context, pixels * 4, vk::MemoryUse::Readback, "oracle depth (readback)");
  } catch (...) {
    release();
    throw;
  }
}

GraphicsRasterizer::~GraphicsRasterizer() { release(); }

void GraphicsRasterizer::release() {
  destroyOracleDraw(context_.device(), pipelines_, pipelineLayout_, framebuffer_, renderPass_);
  destroyAttachment(context_, color_);
  destroyAttachment(context_, depth_);
  vertices_ = vk::Buffer();
  staging_ = vk::Buffer();
}

void GraphicsRasterizer::createRenderPass() {
  const VkFormat colorFormats[] = {kIdFormat};
  renderPass_ = createReadbackRenderPass(context_, colorFormats, depthFormat_);
}

void GraphicsRasterizer::createAttachments() {
  color_ = createAttachment(context_, width_, height_, kIdFormat, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                            VK_IMAGE_ASPECT_COLOR_BIT);
  depth_ = createAttachment(context_, width_, height_, depthFormat_, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                            VK_IMAGE_ASPECT_DEPTH_BIT);
  const VkImageView views[2] = {color_.view, depth_.view};
  framebuffer_ = createReadbackFramebuffer(context_, renderPass_, views, width_, height_);
}

void GraphicsRasterizer::createPipelines() {
  const VkDevice device = context_.device();
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  HMB_VK_CHECK(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &pipelineLayout_));

  const VkVertexInputBindingDescription binding{0, sizeof(Vertex), VK_VERTEX_INPUT_RATE_VERTEX};
  const VkVertexInputAttributeDescription attributes[2] = {
      {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(Vertex, clip)},
      {1, 0, VK_FORMAT_R32_UINT, offsetof(Vertex, id)},
  };
  VkPipelineVertexInputStateCreateInfo vertexInput{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  vertexInput.vertexBindingDescriptionCount = 1;
  vertexInput.pVertexBindingDescriptions = &binding;
  vertexInput.vertexAttributeDescriptionCount = 2;
  vertexInput.pVertexAttributeDescriptions = attributes;
  createOraclePipelines(device, {kOracle_vert, kOracle_frag}, vertexInput, 1, VK_COLOR_COMPONENT_R_BIT,
                        pipelineLayout_, renderPass_, width_, height_, pipelines_);
}

void* GraphicsRasterizer::reserveVertices(VkDeviceSize bytes) {
  if (vertices_.size() < bytes) {
    // Grow by half again so a benchmark ramping up its triangle count reallocates rarely.
    const VkDeviceSize size = std::max(bytes, vertices_.size() + vertices_.size() / 2);
    staging_ = vk::Buffer();
    // Device-local so the timed draw reads fast memory; written directly where that memory
    // is also host-visible (CPU devices, resizable BAR), else through a staging buffer.
    vertices_ = vk::Buffer(context_, size, vk::MemoryUse::Device, "oracle vertices", VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
    if (!vertices_.mapped()) staging_ = vk::Buffer(context_, size, vk::MemoryUse::Upload, "oracle vertex staging");
  }
  return vertices_.mapped() ? vertices_.mapped() : staging_.mapped();
}

OracleImage GraphicsRasterizer::rasterize(std::span<const OracleTriangle> triangles) {
  const VkDeviceSize vertexBytes = VkDeviceSize(triangles.size()) * 3 * sizeof(Vertex);
  if (triangles.size() > UINT32_MAX / 3) throw Error("graphics oracle: too many triangles for one draw");

  std::vector<DrawSpan> draws;
  if (!triangles.empty()) {
    auto* out = static_cast<Vertex*>(reserveVertices(vertexBytes));
    for (size_t t = 0; t < triangles.size(); ++t) {
      const OracleTriangle& tri = triangles[t];
      for (int v = 0; v < 3; ++v) {
        Vertex& vertex = out[3 * t + v];
        std::memcpy(vertex.clip, &tri.clip[v], sizeof(vertex.clip));
        vertex.id = tri.id;
      }
      addTriangle(draws, uint32_t(t), tri.doubleSided);
    }
  }

  context_.submitAndWait([&](VkCommandBuffer cmd) {
    if (staging_.mapped() && vertexBytes > 0) {
      // The previous call's draw read the vertex buffer; then this call's upload fills it.
      VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_VERTEX_INPUT_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before,
                           0, nullptr, 0, nullptr);
      const VkBufferCopy region{0, 0, vertexBytes};
      vkCmdCopyBuffer(cmd, staging_.handle(), vertices_.handle(), 1, &region);
      VkMemoryBarrier after{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
      after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
      after.dstAccessMask = VK_ACCESS_VERTEX_ATTRIBUTE_READ_BIT;
      vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_VERTEX_INPUT_BIT, 0, 1, &after,
                           0, nullptr, 0, nullptr);
    }
    timer_.begin(cmd);  // after the upload above, which is not timed

    VkClearValue clears[2]{};
    clears[0].color.uint32[0] = 0;
    clears[1].depthStencil = {0.0f, 0};  // the far plane
    beginReadbackPass(cmd, renderPass_, framebuffer_, width_, height_, clears);
    if (!draws.empty()) {
      const VkDeviceSize offset = 0;
      const VkBuffer vertexBuffer = vertices_.handle();
      vkCmdBindVertexBuffers(cmd, 0, 1, &vertexBuffer, &offset);
      recordDrawSpans(cmd, pipelines_, draws);
    }
    vkCmdEndRenderPass(cmd);
    timer_.end(cmd);

    // The render pass left both attachments in TRANSFER_SRC_OPTIMAL (its outgoing dependency
    // orders the copies after the attachment writes).
    VkBufferImageCopy region{};
    region.imageExtent = {width_, height_, 1};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    vkCmdCopyImageToBuffer(cmd, color_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, idsReadback_.handle(), 1, &region);
    region.imageSubresource.aspectMask = VK_IMAGE_ASPECT_DEPTH_BIT;
    vkCmdCopyImageToBuffer(cmd, depth_.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, depthReadback_.handle(), 1,
                           &region);
    barrierToHost(cmd);
  });

  lastDrawMs_ = timer_.milliseconds();

  OracleImage image;
  image.width = width_;
  image.height = height_;
  image.ids = idsReadback_.download<uint32_t>();
  if (depthFormat_ == VK_FORMAT_X8_D24_UNORM_PACK32) {
    // 24-bit unorm in the low bits of each texel.
    const std::vector<uint32_t> raw = depthReadback_.download<uint32_t>();
    image.depth.resize(raw.size());
    for (size_t i = 0; i < raw.size(); ++i) image.depth[i] = float(double(raw[i] & 0xFFFFFFu) / 16777215.0);
  } else {
    image.depth = depthReadback_.download<float>();  // D32 formats copy the depth aspect as plain floats
  }
  return image;
}

OracleImage rasterizeWithGraphicsPipeline(const vk::Context& context, uint32_t width, uint32_t height,
                                          std::span<const OracleTriangle> triangles) {
  GraphicsRasterizer rasterizer(context, width, height);
  return rasterizer.rasterize(triangles);
}

std::vector<OracleTriangle> oracleTriangles(std::span<const glm::vec4> clip,
                                            std::span<const gpu::GpuTriangle> triangles,
                                            const std::vector<bool>& doubleSided) {
  std::vector<OracleTriangle> out(triangles.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const gpu::GpuTriangle& tri = triangles[t];
    out[t].clip[0] = clip[tri.v0];
    out[t].clip[1] = clip[tri.v1];
    out[t].clip[2] = clip[tri.v2];
    out[t].id = static_cast<uint32_t>(t);
    out[t].doubleSided = doubleSided.at(tri.instance);
  }
  return out;
}

double idAgreement(std::span<const glm::uvec2> visibility, const OracleImage& oracle) {
  const size_t pixels = oracle.ids.size();
  if (pixels == 0) return 1.0;
  if (visibility.size() < pixels) throw Error("visibility buffer is smaller than the oracle image");
  size_t same = 0;
  for (size_t i = 0; i < pixels; ++i) {
    const uint32_t expected = oracle.ids[i] == 0 ? HMB_VIS_EMPTY : oracle.ids[i] - 1;
    same += visibility[i].x == expected;
  }
  return double(same) / double(pixels);
}

}  // namespace hmb::oracle
