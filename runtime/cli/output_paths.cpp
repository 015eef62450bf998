#include "runtime/cli/output_paths.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <fstream>

#include "hmblur/error.h"

namespace hmb::cli {
namespace {

namespace fs = std::filesystem;

// Makes the folder if it is missing and proves a file can be created in it (permissions,
// read-only file systems and full quotas all show here; root passes every access() check).
void makeWritableFolder(const fs::path& folder, const std::string& what) {
  std::error_code error;
  if (!folder.empty() && !fs::is_directory(folder, error)) {
    fs::create_directories(folder, error);
    if (error || !fs::is_directory(folder))
      throw Error(what + ": cannot create the folder '" + folder.string() + "'" +
                  (error ? " (" + error.message() + ")" : ""));
  }
  const fs::path probe = (folder.empty() ? fs::path(".") : folder) / (".hmblur-write-check-" + std::to_string(getpid()));
  std::ofstream(probe).close();
  const bool written = fs::exists(probe, error);
  fs::remove(probe, error);
  if (!written) throw Error(what + ": cannot write in '" + (folder.empty() ? "." : folder.string()) + "'");
}

}  // namespace

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

void prepareOutputFile(const std::string& path, std::initializer_list<const char*> extensions, const char* option) {
  if (path.empty()) return;
  const std::string what = std::string(option) + " '" + path + "'";
  const std::string ext = lowerExtension(path);
  if (std::none_of(extensions.begin(), extensions.end(), [&](const char* e) { return ext == e; })) {
    std::string list;
    for (const char* e : extensions) list += (list.empty() ? "" : " or ") + std::string(e);
    throw Error(what + " must end in " + list);
  }
  std::error_code error;
  if (fs::is_directory(path, error)) throw Error(what + " is a folder; name a file");
  makeWritableFolder(fs::path(path).parent_path(), what);
  if (fs::exists(path, error) && access(path.c_str(), W_OK) != 0) throw Error(what + ": the file cannot be written");
}

void prepareOutputFolder(const std::string& path, const char* option) {
  if (path.empty()) return;
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error))
    throw Error(std::string(option) + " '" + path + "' is a file; name a folder");
  makeWritableFolder(fs::path(path), std::string(option) + " '" + path + "'");
}

}  // namespace hmb::cli
