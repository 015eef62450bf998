// One image layer of per-pixel buffers (kernels/shared/layer_layout.h): the samples every
// gather reads (colour, depth, velocity in halves) and the surfaces (normal, object id, velocity, depth),
// bound together (vk::BufferGroup), and a G-buffer's velocities as floats beside them, which
// tile-max reads. The G-buffer and the hybrid's revealed layer (without velocities) are both one.
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
  // Whether a layer keeps its velocities as floats: a G-buffer does, for tile-max.
  enum class Velocities { Kept, None };

  ImageLayer() = default;
  // Takes the two buffers (at least `pixels` uvec4 each) and the velocities (at least
  // HMB_LAYER_VELOCITY_ENTRIES(pixels) vec2; none: an empty buffer).
  ImageLayer(vk::Buffer samples, vk::Buffer surfaces, vk::Buffer velocities = {});
  // New buffers for `pixels` pixels, named "<name> samples", "<name> surfaces" and "<name> velocities".
  static ImageLayer allocate(const vk::Context& context, uint64_t pixels, const std::string& name,
                             Velocities velocities = Velocities::Kept);

  const vk::Buffer& samples() const { return samples_; }    // uvec4: colour, depth, velocity (halves)
  const vk::Buffer& surfaces() const { return surfaces_; }  // uvec4: normal, object id, velocity (halves), depth
  const vk::Buffer& velocities() const { return velocities_; }  // vec2: velocity (floats); no buffer: none kept
  // Binds the layer as a kernel declares it (kernels/shared/layer_bindings.glsl) from
  // firstBinding on: its two buffers, or the table of their addresses for a kernel that binds
  // by address.
  void bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const;
  uint64_t bytes() const { return samples_.size() + surfaces_.size() + velocities_.size(); }

 private:
  vk::Buffer samples_, surfaces_, velocities_;
  vk::BufferGroup group_;
};

// A layer's first `pixels` entries read back and unpacked on the host, as the kernels decode them.
struct LayerContents {
  std::vector<glm::vec3> color;
  std::vector<glm::vec3> normal;  // 0 where the object id is 0
  std::vector<float> depth;
  std::vector<glm::vec2> velocity;  // the velocities where the layer keeps them, else the surfaces' half floats
  std::vector<uint32_t> objectId;
};
LayerContents downloadLayer(const ImageLayer& layer, uint64_t pixels);
// The packed pixels of a layer made on the host (tests' inputs): samples, surfaces and the
// velocities as a G-buffer keeps them (HMB_LAYER_VELOCITY_ENTRIES of them, the last unused for
// an odd count).
struct PackedLayer {
  std::vector<glm::uvec4> samples, surfaces;
  std::vector<glm::vec2> velocities;
};
PackedLayer packLayer(const LayerContents& contents);

}  // namespace hmb::passes
