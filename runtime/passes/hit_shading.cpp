#include "hmblur/hit_shading.h"

#include "hmblur/error.h"
#include "runtime/vulkan/glsl_compiler.h"
#include "runtime/vulkan/kernel_registry.h"

namespace hmb::passes {
namespace {

constexpr const char* kPublicInclude = "hmblur/hit_shading.glsl";
constexpr const char* kPublicIncludeInTree = "include/hmblur/hit_shading.glsl";

}  // namespace

const vk::KernelBuilds& HitShading::buildsFor(std::string_view kernelName) const {
  if (!custom()) throw Error("HitShading::buildsFor: the library's shading has its kernels built in");
  const std::lock_guard lock(mutex_);
  if (const auto found = builds_.find(kernelName); found != builds_.end()) return found->second;
  vk::GlslCompileInput input;
  input.kernel = std::string(kernelName);
  // The user's text may include the API's GLSL as an engine's shaders do.
  input.files = {{kPublicInclude, std::string(vk::findKernelSource(kPublicIncludeInTree)->text)}};
  // Both includes are there whichever is used: the includes are expanded before the
  // preprocessor drops the library's default's branch.
  input.files.emplace("custom_shade_hit.glsl", "#line 1 \"shadeHit\"\n" + shadeHit_ + "\n");
  input.files.emplace("custom_shade_miss.glsl", "#line 1 \"shadeMiss\"\n" + shadeMiss_ + "\n");
  if (!shadeHit_.empty()) input.defines.push_back("HMB_CUSTOM_SHADE_HIT");
  if (!shadeMiss_.empty()) input.defines.push_back("HMB_CUSTOM_SHADE_MISS");
  input.description = shadeMiss_.empty()   ? "the user's shadeHit"
                      : shadeHit_.empty()  ? "the user's shadeMiss"
                                           : "the user's shadeHit and shadeMiss";
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
