// Kernels compiled from GLSL while the program runs, with glslang's library: a kernel's own
// text (embedded, kernel_registry.h) with more defines and more include files than its build
// had, for code a user supplies (passes::HitShading). The result is what glslangValidator makes
// of the same text at build time (cmake/EmbedKernels.cmake): Vulkan 1.1, SPIR-V 1.3.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace hmb::vk {

struct GlslCompileInput {
  std::string kernel;                          // "reveal/reveal_background" (its .comp under kernels/)
  std::vector<std::string> defines;            // "NAME" or "NAME=VALUE"
  std::map<std::string, std::string> files;    // include name -> text, found before the tree's files
  std::string description;                     // what the error says was compiled, e.g. "the engine's shadeHit"
};

// The SPIR-V words; throws hmb::Error with the compiler's first error in one line.
std::vector<uint32_t> compileKernelGlsl(const GlslCompileInput& input);

}  // namespace hmb::vk
