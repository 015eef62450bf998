#include "hmblur/hit_shading.h"

#include "hmblur/error.h"
#include "runtime/vulkan/glsl_compiler.h"
#include "runtime/vulkan/kernel_registry.h"

namespace hmb::passes {

const vk::KernelBuilds& HitShading::buildsFor(std::string_view kernelName) const {
  if (!custom()) throw Error("HitShading::buildsFor: the library's shading has its kernels built in");
  const std::lock_guard lock(mutex_);
  if (const auto found = builds_.find(kernelName); found != builds_.end()) return found->second;
  vk::GlslCompileInput input;
  input.kernel = std::string(kernelName);
  input.defines = {"HMB_CUSTOM_SHADE_HIT"};
  input.files = {{"custom_shade_hit.glsl", "#line 1 \"shadeHit\"\n" + glsl_ + "\n"}};
  input.description = "the user's shadeHit";
  vk::KernelBuilds builds;
  builds.plain = vk::compileKernelGlsl(input);
  // The address build too where the kernel has one (cmake/EmbedKernels.cmake, ADDRESS_VARIANTS).
  if (vk::findKernelIfBuilt(std::string(kernelName) + std::string(vk::kByAddressSuffix))) {
    input.defines.push_back("HMB_BIND_BY_ADDRESS");
    builds.byAddress = vk::compileKernelGlsl(input);
  }
  return builds_.emplace(std::string(kernelName), std::move(builds)).first->second;
}

}  // namespace hmb::passes
