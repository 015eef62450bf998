// One image layer of per-pixel buffers (kernels/shared/layer_layout.h): the samples every
// gather reads (colour, depth, velocity in halves) and the surfaces (normal, object id, velocity, depth),
// bound together (vk::BufferGroup). The G-buffer and the hybrid's revealed layer are both one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/buffer.h"
#include "runtime/vulkan/buffer_group.h"

namespace hmb::passes {

class ImageLayer {
 public:
  ImageLayer() = default;
  // Takes the two buffers (at least `pixels` uvec4 each).
  ImageLayer(vk::Buffer samples, vk::Buffer surfaces);
  // Two new buffers of `pixels` entries, named "<name> samples" and "<name> surfaces".
  static ImageLayer allocate(const vk::Context& context, uint64_t pixels, const std::string& name);

  const vk::Buffer& samples() const { return samples_; }    // uvec4: colour, depth, velocity (halves)
  const vk::Buffer& surfaces() const { return surfaces_; }  // uvec4: normal, object id, velocity (halves), depth
  // Binds the layer as a kernel declares it (kernels/shared/layer_bindings.glsl) from
  // firstBinding on: its two buffers, or the table of their addresses for a kernel that binds
  // by address.
  void bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const;
  uint64_t bytes() const { return samples_.size() + surfaces_.size(); }

 private:
  vk::Buffer samples_, surfaces_;
  vk::BufferGroup group_;
};

// A layer's first `pixels` entries read back and unpacked on the host, as the kernels decode them.
struct LayerContents {
  std::vector<glm::vec3> color;
  std::vector<glm::vec3> normal;  // 0 where the object id is 0
  std::vector<float> depth;
  std::vector<glm::vec2> velocity;
  std::vector<uint32_t> objectId;
};
LayerContents downloadLayer(const ImageLayer& layer, uint64_t pixels);
// The packed pixels of a layer made on the host (tests' inputs): samples and surfaces.
struct PackedLayer {
  std::vector<glm::uvec4> samples, surfaces;
};
PackedLayer packLayer(const LayerContents& contents);

}  // namespace hmb::passes
