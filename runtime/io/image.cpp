#include "hmblur/image.h"

namespace hmb::io {

const ImageLayer* LayeredImage::find(const std::string& name) const {
  for (const ImageLayer& layer : layers) {
    if (layer.name == name) return &layer;
  }
  return nullptr;
}

}  // namespace hmb::io
