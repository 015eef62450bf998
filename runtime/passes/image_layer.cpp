#include "runtime/passes/image_layer.h"

#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/shared/layer_layout.h"

namespace hmb::passes {

ImageLayer::ImageLayer(vk::Buffer color, vk::Buffer normalDepth, vk::Buffer velocity, vk::Buffer objectId)
    : color_(std::move(color)),
      normalDepth_(std::move(normalDepth)),
      velocity_(std::move(velocity)),
      objectId_(std::move(objectId)) {}

void ImageLayer::bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const {
  static_assert(sizeof(gpu::LayerTable) == 4 * sizeof(uint64_t));
  const vk::Buffer* members[] = {&color_, &normalDepth_, &velocity_, &objectId_};  // gpu::LayerTable's order
  group_.bind(bindings, firstBinding, byAddress, members);
}

ImageLayer ImageLayer::allocate(const vk::Context& context, uint64_t pixels, const std::string& name) {
  return ImageLayer(vk::Buffer(context, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, name + " colour"),
                    vk::Buffer(context, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, name + " normal-depth"),
                    vk::Buffer(context, pixels * sizeof(glm::vec2), vk::MemoryUse::Device, name + " velocity"),
                    vk::Buffer(context, pixels * sizeof(uint32_t), vk::MemoryUse::Device, name + " object id"));
}

}  // namespace hmb::passes
