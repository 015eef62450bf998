// Images side by side with a caption under each (a demo's comparison strip): the text drawn
// with the system's sans-serif font, found by fontconfig and rasterized by FreeType.
#pragma once

#include <string>
#include <vector>

#include "hmblur/image.h"

namespace hmb::io {

struct CaptionedImage {
  Rgba8Image image;
  std::vector<std::string> caption;  // one entry per line, e.g. the method, then its time and PSNR
};

struct LabelledStrip {
  Rgba8Image image;
  bool captioned = false;  // false: no font was found; the strip has blank caption bands
};

// The images left to right (all of one size), each above a band that holds its caption in
// light text on dark grey, at a text size that follows the image height.
LabelledStrip labelledStrip(const std::vector<CaptionedImage>& panels);

}  // namespace hmb::io
