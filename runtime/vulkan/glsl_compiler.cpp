#include "runtime/vulkan/glsl_compiler.h"

#include <filesystem>
#include <memory>
#include <mutex>
#include <sstream>
#include <string_view>

#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>

#include "hmblur/error.h"
#include "runtime/vulkan/kernel_registry.h"

namespace hmb::vk {
namespace {

// glslang's process-wide state, made once; it lives as long as the program.
void initializeGlslang() {
  static std::once_flag once;
  std::call_once(once, [] { glslang_initialize_process(); });
}

// The text with every #include "..." replaced by the included file's text, as the build's
// glslangValidator resolves them: the user's files by name, else the path relative to the
// including file's folder in the source tree. The headers' include guards keep repeats out; #line
// keeps the compiler's messages pointing at the right file and line.
std::string expandIncludes(const std::string& path, std::string_view text, const GlslCompileInput& input, int depth) {
  if (depth > 32) throw Error("GLSL includes nest deeper than 32 at '" + path + "'");
  std::string out;
  std::istringstream lines{std::string(text)};
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const size_t hash = line.find_first_not_of(" \t");
    const bool isInclude = hash != std::string::npos && line.compare(hash, 8, "#include") == 0;
    const size_t open = isInclude ? line.find('"', hash) : std::string::npos;
    const size_t close = open == std::string::npos ? open : line.find('"', open + 1);
    if (close == std::string::npos) {
      out += line + "\n";
      continue;
    }
    const std::string name = line.substr(open + 1, close - open - 1);
    std::string included;
    std::string_view includedText;
    if (const auto own = input.files.find(name); own != input.files.end()) {
      included = own->first;
      includedText = own->second;
    } else {
      included = (std::filesystem::path(path).parent_path() / name).lexically_normal().generic_string();
      const KernelSource* source = findKernelSource(included);
      if (!source) throw Error("'" + path + "' line " + std::to_string(number) + " includes '" + name + "', which is not there");
      includedText = source->text;
    }
    out += "#line 1 \"" + included + "\"\n";
    out += expandIncludes(included, includedText, input, depth + 1);
    out += "#line " + std::to_string(number + 1) + " \"" + path + "\"\n";
  }
  return out;
}

// The first error line of a glslang log, without its "ERROR: " prefix.
std::string firstError(const char* log) {
  std::istringstream lines(log ? log : "");
  std::string line;
  while (std::getline(lines, line))
    if (line.rfind("ERROR: ", 0) == 0 && line.find("compilation terminated") == std::string::npos)
      return line.substr(7);
  return log && *log ? std::string(log).substr(0, std::string(log).find('\n')) : "unknown error";
}

}  // namespace

std::vector<uint32_t> compileKernelGlsl(const GlslCompileInput& input) {
  const std::string path = "kernels/" + input.kernel + ".comp";
  const KernelSource* source = findKernelSource(path);
  if (!source) throw Error("kernel '" + input.kernel + "' has no GLSL text built into this binary");
  initializeGlslang();
  std::string preamble;
  for (const std::string& define : input.defines) {
    const size_t equals = define.find('=');
    preamble += "#define " + (equals == std::string::npos ? define + " 1" : define.substr(0, equals) + " " +
                                                                               define.substr(equals + 1)) + "\n";
  }
  const std::string text = expandIncludes(path, source->text, input, 0);
  glslang_input_t in{};
  in.language = GLSLANG_SOURCE_GLSL;
  in.stage = GLSLANG_STAGE_COMPUTE;
  in.client = GLSLANG_CLIENT_VULKAN;
  in.client_version = GLSLANG_TARGET_VULKAN_1_1;
  in.target_language = GLSLANG_TARGET_SPV;
  in.target_language_version = GLSLANG_TARGET_SPV_1_3;
  in.code = text.c_str();
  in.default_version = 450;
  in.default_profile = GLSLANG_NO_PROFILE;
  in.messages = GLSLANG_MSG_DEFAULT_BIT;
  in.resource = glslang_default_resource();

  const std::string what = "kernel '" + input.kernel + "'" + (input.description.empty() ? "" : " with " + input.description);
  std::unique_ptr<glslang_shader_t, decltype(&glslang_shader_delete)> shader(glslang_shader_create(&in),
                                                                             glslang_shader_delete);
  glslang_shader_set_preamble(shader.get(), preamble.c_str());
  if (!glslang_shader_preprocess(shader.get(), &in) || !glslang_shader_parse(shader.get(), &in))
    throw Error(what + " does not compile: " + firstError(glslang_shader_get_info_log(shader.get())));
  std::unique_ptr<glslang_program_t, decltype(&glslang_program_delete)> program(glslang_program_create(),
                                                                                glslang_program_delete);
  glslang_program_add_shader(program.get(), shader.get());
  if (!glslang_program_link(program.get(), GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT))
    throw Error(what + " does not link: " + firstError(glslang_program_get_info_log(program.get())));
  glslang_program_SPIRV_generate(program.get(), GLSLANG_STAGE_COMPUTE);
  std::vector<uint32_t> words(glslang_program_SPIRV_get_size(program.get()));
  glslang_program_SPIRV_get(program.get(), words.data());
  if (words.empty()) throw Error(what + " gave no SPIR-V");
  return words;
}

}  // namespace hmb::vk
