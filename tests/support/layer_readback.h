// An image layer read back as the tests read it: colour with alpha 1, normal and depth together,
// velocity and object id, unpacked as the kernels decode them (passes::downloadLayer).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/passes/image_layer.h"

namespace hmb::test {

struct LayerReadback {
  std::vector<glm::vec4> color, normalDepth;  // rgb a = 1; xyz world normal, w camera-space depth
  std::vector<glm::vec2> velocity;            // pixels per frame
  std::vector<uint32_t> objectId;
};

inline LayerReadback readLayer(const passes::ImageLayer& layer, uint64_t pixels) {
  const passes::LayerContents c = passes::downloadLayer(layer, pixels);
  LayerReadback out;
  for (size_t i = 0; i < c.color.size(); ++i) {
    out.color.emplace_back(c.color[i], 1.0f);
    out.normalDepth.emplace_back(c.normal[i], c.depth[i]);
  }
  out.velocity = c.velocity;
  out.objectId = c.objectId;
  return out;
}

}  // namespace hmb::test
