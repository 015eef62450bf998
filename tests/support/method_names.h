// The methods tests render by name: the renderer's (parseMethod), and the hybrid without its
// shutter rays, the paper's method (ray mask, reveal, composite), which the default hybrid
// leaves to the rays (passes::HybridStage::plan).
#pragma once

#include <string>

#include "hmblur/renderer.h"

namespace hmb::test {

inline constexpr const char* kHybridReveal = "hybrid-reveal";

inline void setMethod(RenderSettings& settings, const std::string& name) {
  settings.method = parseMethod(name == kHybridReveal ? "hybrid" : name);
  if (name == kHybridReveal) settings.hybrid.shutterRays = 0;
}

}  // namespace hmb::test
