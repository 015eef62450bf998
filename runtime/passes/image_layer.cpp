#include "runtime/passes/image_layer.h"

#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "hmblur/error.h"
#include "kernels/shared/layer_layout.h"

namespace hmb::passes {

ImageLayer::ImageLayer(vk::Buffer samples, vk::Buffer surfaces, vk::Buffer velocities)
    : samples_(std::move(samples)), surfaces_(std::move(surfaces)), velocities_(std::move(velocities)) {}

void ImageLayer::bind(vk::Bindings& bindings, uint32_t firstBinding, bool byAddress) const {
  static_assert(sizeof(gpu::LayerTable) == 2 * sizeof(uint64_t));
  const vk::Buffer* members[] = {&samples_, &surfaces_};  // gpu::LayerTable's order
  group_.bind(bindings, firstBinding, byAddress, members);
}

ImageLayer ImageLayer::allocate(const vk::Context& context, uint64_t pixels, const std::string& name,
                                Velocities velocities) {
  return ImageLayer(vk::Buffer(context, pixels * sizeof(glm::uvec4), vk::MemoryUse::Device, name + " samples"),
                    vk::Buffer(context, pixels * sizeof(glm::uvec4), vk::MemoryUse::Device, name + " surfaces"),
                    velocities == Velocities::Kept
                        ? vk::Buffer(context, HMB_LAYER_VELOCITY_ENTRIES(pixels) * sizeof(glm::vec2),
                                     vk::MemoryUse::Device, name + " velocities")
                        : vk::Buffer());
}

LayerContents downloadLayer(const ImageLayer& layer, uint64_t pixels) {
  const std::vector<glm::uvec4> samples = layer.samples().download<glm::uvec4>();
  const std::vector<glm::uvec4> surfaces = layer.surfaces().download<glm::uvec4>();
  const std::vector<glm::vec2> velocities =
      layer.velocities().handle() ? layer.velocities().download<glm::vec2>() : std::vector<glm::vec2>();
  if (samples.size() < pixels || surfaces.size() < pixels || (layer.velocities().handle() && velocities.size() < pixels))
    throw Error("image layer of " + std::to_string(samples.size()) + " pixels read back as " + std::to_string(pixels));
  LayerContents out;
  out.color.reserve(pixels);
  out.normal.reserve(pixels);
  out.depth.reserve(pixels);
  out.velocity.reserve(pixels);
  out.objectId.reserve(pixels);
  for (uint64_t i = 0; i < pixels; ++i) {
    out.color.push_back(gpu::sampleColor(samples[i]));
    out.normal.push_back(gpu::surfaceNormal(surfaces[i]));
    out.depth.push_back(gpu::sampleDepth(samples[i]));
    out.velocity.push_back(velocities.empty() ? gpu::surfaceVelocity(surfaces[i]) : velocities[i]);
    out.objectId.push_back(gpu::surfaceObjectId(surfaces[i]));
  }
  return out;
}

PackedLayer packLayer(const LayerContents& c) {
  const size_t pixels = c.color.size();
  if (c.normal.size() != pixels || c.depth.size() != pixels || c.velocity.size() != pixels ||
      c.objectId.size() != pixels)
    throw Error("packLayer: the layer's components differ in length");
  PackedLayer out;
  out.samples.reserve(pixels);
  out.surfaces.reserve(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    out.samples.push_back(gpu::packLayerSample(c.color[i], c.depth[i], c.velocity[i]));
    out.surfaces.push_back(gpu::packLayerSurface(c.normal[i], c.objectId[i], c.depth[i], c.velocity[i]));
  }
  out.velocities.reserve(HMB_LAYER_VELOCITY_ENTRIES(pixels));
  for (size_t i = 0; i < pixels; ++i) out.velocities.push_back(gpu::layerVelocityEntry(c.velocity[i]));
  out.velocities.resize(HMB_LAYER_VELOCITY_ENTRIES(pixels), glm::vec2(0.0f));
  return out;
}

}  // namespace hmb::passes
