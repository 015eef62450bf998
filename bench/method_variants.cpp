#include "bench/method_variants.h"

#include <algorithm>

#include "hmblur/error.h"

namespace hmb::bench {

void applyMethodVariant(const std::string& name, const std::vector<std::string>& accepted, RenderSettings& settings) {
  if (std::find(accepted.begin(), accepted.end(), name) == accepted.end()) {
    std::string list;
    for (const std::string& a : accepted) list += (list.empty() ? "" : ", ") + a;
    throw Error("method '" + name + "' is not one of " + list);
  }
  constexpr std::string_view kCurved = "-curved", kNoShutterRays = "-without-shutter-rays";
  const bool curved = name.ends_with(kCurved), noShutterRays = name.ends_with(kNoShutterRays);
  const size_t suffix = curved ? kCurved.size() : (noShutterRays ? kNoShutterRays.size() : 0);
  settings.method = parseMethod(name.substr(0, name.size() - suffix));
  settings.postprocess.motionPath = curved ? passes::MotionPath::Curved : passes::MotionPath::Linear;
  if (noShutterRays) settings.hybrid.shutterRays = 0;
}

}  // namespace hmb::bench
