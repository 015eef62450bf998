// The image size a stage's per-pixel buffers were last made for. A stage's prepare() reads
//   if (size_.changesTo(width, height)) { ...make the buffers...; size_.madeFor(width, height); }
// and changesTo forgets the old size at once, so buffers whose making failed half-way (a frame
// too large for the device) never pass for sized; record() checks with requireMadeFor().
#pragma once

#include <cstdint>
#include <string>

#include "hmblur/error.h"

namespace hmb::passes {

class ImageSize {
 public:
  bool changesTo(uint32_t width, uint32_t height) {
    if (width == width_ && height == height_) return false;
    forget();
    return true;
  }
  void madeFor(uint32_t width, uint32_t height) {
    width_ = width;
    height_ = height;
  }
  void forget() { width_ = height_ = 0; }
  // Throws hmb::Error naming `stage` when width x height is not the size the buffers were made for.
  void requireMadeFor(const char* stage, uint32_t width, uint32_t height) const {
    if (width != width_ || height != height_)
      throw Error(std::string(stage) + ": inputs are " + std::to_string(width) + "x" + std::to_string(height) +
                  " but the stage was prepared for " + std::to_string(width_) + "x" + std::to_string(height_));
  }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  uint32_t width_ = 0, height_ = 0;
};

}  // namespace hmb::passes
