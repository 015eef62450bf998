// The method names the benchmark suites take: the renderer's methods; and NAME-curved, the
// same along curved paths (--motion-path curved), so that both paths are measured in one run.
#pragma once

#include <string>
#include <vector>

#include "hmblur/renderer.h"

namespace hmb::bench {

// The settings a name stands for, on top of `settings`: its method and motion path. Throws
// hmb::Error naming `accepted` when the name is not among them.
void applyMethodVariant(const std::string& name, const std::vector<std::string>& accepted, RenderSettings& settings);

}  // namespace hmb::bench
