// Mesa's llvmpipe keys its on-disk shader cache without LP_NATIVE_VECTOR_WIDTH, so a run at
// 128-bit vectors can load code an earlier 256-bit run compiled: kernels then run 8 lanes wide
// while the device reports subgroups of 4, and the graphics pipeline's vertex stage overruns
// buffers sized for 4 (heap corruption in the graphics-raster oracle). Every test executable
// links this file: a run that sets the width, and no cache folder of its own, gets a cache
// folder for that width, before any Vulkan driver is loaded.
#include <cstdlib>
#include <filesystem>
#include <string>

namespace {

const bool kCachePerVectorWidth = [] {
  const char* width = std::getenv("LP_NATIVE_VECTOR_WIDTH");
  if (!width || std::getenv("MESA_SHADER_CACHE_DIR")) return false;
  std::string base;
  if (const char* cache = std::getenv("XDG_CACHE_HOME"))
    base = cache;
  else if (const char* home = std::getenv("HOME"))
    base = std::string(home) + "/.cache";
  else
    base = std::filesystem::temp_directory_path().string();
  return setenv("MESA_SHADER_CACHE_DIR", (base + "/mesa_shader_cache_lp" + width).c_str(), 0) == 0;
}();

}  // namespace
