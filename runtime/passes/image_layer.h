// One image layer of per-pixel buffers (kernels/shared/layer_layout.h): colour, normal and
// depth, velocity, object id, bound together (vk::BufferGroup). The G-buffer and the hybrid's
// revealed layer are both one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "runtime/vulkan/buffer.h"
#include "runtime/vulkan/buffer_group.h"

namespace hmb::passes {

class ImageLayer {
 public:
  ImageLayer() = default;
  // Takes the four buffers (at least `pixels` entries each).
  ImageLayer(vk::Buffer color, vk::Buffer normalDepth, vk::Buffer velocity, vk::Buffer objectId);
  // Four new buffers of `pixels` entries, named "<name> colour", "<name> normal-depth", ...
  static ImageLayer allocate(const vk::Context& context, uint64_t pixels, const std::string& name);

  const vk::Buffer& color() const { return color_; }              // vec4 linear RGB, a = 1
  const vk::Buffer& normalDepth() const { return normalDepth_; }  // vec4 world normal, w camera-space depth
  const vk::Buffer& velocity() const { return velocity_; }        // vec2 pixels per frame, y down
  const vk::Buffer& objectId() const { return objectId_; }        // uint, 0 = background
  // Binds the layer as a kernel declares it (kernels/shared/layer_bindings.glsl) from
  // firstBinding on: its four buffers, or the table of their addresses for a kernel that binds
  // by address.
  void bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const;
  uint64_t bytes() const { return color_.size() + normalDepth_.size() + velocity_.size() + objectId_.size(); }

 private:
  vk::Buffer color_, normalDepth_, velocity_, objectId_;
  vk::BufferGroup group_;
};

}  // namespace hmb::passes
