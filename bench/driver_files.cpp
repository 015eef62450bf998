#include "bench/driver_files.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <vector>

#include <nlohmann/json.hpp>

#include "hmblur/error.h"

namespace hmb::bench {
namespace {

namespace fs = std::filesystem;

// Set in the program started again, so that it does not start itself once more.
constexpr const char* kAppliedVariable = "HMB_BENCH_DRIVER_FILES";

std::vector<fs::path> manifestsIn(const fs::path& folder) {
  std::vector<fs::path> found;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
    if (entry.is_regular_file() && entry.path().extension() == ".json") found.push_back(entry.path());
  std::sort(found.begin(), found.end());
  return found;
}

// The folder of the library a manifest names; the loader finds a bare file name itself.
std::string libraryFolder(const fs::path& manifest) {
  nlohmann::json json;
  try {
    std::ifstream in(manifest);
    json = nlohmann::json::parse(in);
  } catch (const std::exception&) {
    throw Error("--driver-files: " + manifest.string() + " is not an ICD manifest (not JSON)");
  }
  if (!json.contains("ICD") || !json["ICD"].contains("library_path") || !json["ICD"]["library_path"].is_string())
    throw Error("--driver-files: " + manifest.string() + " is not an ICD manifest (no ICD.library_path)");
  fs::path library = json["ICD"]["library_path"].get<std::string>();
  if (!library.has_parent_path()) return "";
  if (library.is_relative()) library = manifest.parent_path() / library;
  if (!fs::exists(library))
    throw Error("--driver-files: " + manifest.string() + " names a missing library " + library.string());
  return library.parent_path().string();
}

std::string join(const std::vector<std::string>& parts) {
  std::string out;
  for (const std::string& p : parts)
    if (!p.empty() && (":" + out + ":").find(":" + p + ":") == std::string::npos) out += (out.empty() ? "" : ":") + p;
  return out;
}

std::string cacheHome() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return xdg;
  if (const char* home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache";
  return fs::temp_directory_path().string();
}

}  // namespace

DriverFiles resolveDriverFiles(const std::string& path) {
  std::error_code error;
  const fs::path given = fs::absolute(path, error);
  if (error || !fs::exists(given)) throw Error("--driver-files: " + path + " does not exist");
  std::vector<fs::path> manifests;
  if (fs::is_directory(given)) {
    manifests = manifestsIn(given);
    if (manifests.empty()) manifests = manifestsIn(given / "usr/share/vulkan/icd.d");
    if (manifests.empty())
      throw Error("--driver-files: " + path + " holds no ICD manifest (*.json, or usr/share/vulkan/icd.d/*.json)");
  } else {
    manifests.push_back(given);
  }
  DriverFiles files;
  std::vector<std::string> names, folders;
  for (const fs::path& manifest : manifests) {
    const fs::path canonical = fs::weakly_canonical(manifest);
    names.push_back(canonical.string());
    folders.push_back(libraryFolder(canonical));
  }
  files.manifests = join(names);
  files.libraryPaths = join(folders);
  files.shaderCache = cacheHome() + "/hmblur/driver-shader-cache/" +
                      std::to_string(std::hash<std::string>{}(files.manifests) % 1000000007u);
  return files;
}

void runOnDriverFiles(const std::string& path, char** argv) {
  const DriverFiles files = resolveDriverFiles(path);
  if (const char* applied = std::getenv(kAppliedVariable); applied && files.manifests == applied) return;
  std::string libraries = files.libraryPaths;
  if (const char* old = std::getenv("LD_LIBRARY_PATH"); old && *old)
    libraries = libraries.empty() ? std::string(old) : libraries + ":" + old;
  setenv("VK_DRIVER_FILES", files.manifests.c_str(), 1);
  unsetenv("VK_ICD_FILENAMES");  // the variable's older name: one driver list only
  if (!libraries.empty()) setenv("LD_LIBRARY_PATH", libraries.c_str(), 1);
  // llvmpipe's cache key leaves the vector width out (docs/devices.md, "A second driver").
  if (!std::getenv("MESA_SHADER_CACHE_DIR")) {
    const char* width = std::getenv("LP_NATIVE_VECTOR_WIDTH");
    const std::string folder = files.shaderCache + "-width-" + (width && *width ? width : "default");
    setenv("MESA_SHADER_CACHE_DIR", folder.c_str(), 1);
  }
  setenv(kAppliedVariable, files.manifests.c_str(), 1);
  execv("/proc/self/exe", argv);
  throw Error(std::string("--driver-files: could not start hmblur-bench again: ") + std::strerror(errno));
}

}  // namespace hmb::bench
