#include "runtime/passes/image_layer.h"

#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "kernels/shared/layer_layout.h"
#include "runtime/error.h"
#include "runtime/vulkan/context.h"

namespace hmb::passes {

ImageLayer::ImageLayer(const vk::Context& context, vk::Buffer color, vk::Buffer normalDepth, vk::Buffer velocity,
                       vk::Buffer objectId)
    : color_(std::move(color)),
      normalDepth_(std::move(normalDepth)),
      velocity_(std::move(velocity)),
      objectId_(std::move(objectId)) {
  if (context.info().bufferDeviceAddress) {
    const gpu::LayerTable table{color_.address(), normalDepth_.address(), velocity_.address(), objectId_.address()};
    table_ = vk::uploadedBuffer(context, std::vector<gpu::LayerTable>{table}, color_.name() + " (layer table)");
  }
}

void ImageLayer::appendBindings(std::vector<const vk::Buffer*>& bindings, bool byAddress) const {
  if (byAddress) {
    if (!table_.handle()) throw Error("image layer '" + color_.name() + "' has no table of addresses on this device");
    bindings.push_back(&table_);
    return;
  }
  bindings.insert(bindings.end(), {&color_, &normalDepth_, &velocity_, &objectId_});
}

ImageLayer ImageLayer::allocate(const vk::Context& context, uint64_t pixels, const std::string& name) {
  return ImageLayer(context, vk::Buffer(context, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, name + " colour"),
                    vk::Buffer(context, pixels * sizeof(glm::vec4), vk::MemoryUse::Device, name + " normal-depth"),
                    vk::Buffer(context, pixels * sizeof(glm::vec2), vk::MemoryUse::Device, name + " velocity"),
                    vk::Buffer(context, pixels * sizeof(uint32_t), vk::MemoryUse::Device, name + " object id"));
}

}  // namespace hmb::passes
