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
  constexpr std::string_view kCurved = "-curved";
  const bool curved = name.ends_with(kCurved);
  settings.method = parseMethod(name.substr(0, name.size() - (curved ? kCurved.size() : 0)));
  settings.postprocess.motionPath = curved ? passes::MotionPath::Curved : passes::MotionPath::Linear;
}

}  // namespace hmb::bench
