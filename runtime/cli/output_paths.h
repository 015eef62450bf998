// Where the hmblur commands write, checked before any work: one rule for every output. A
// folder that does not exist is created (a file's folder, or a folder named as the output);
// a place that cannot be written is a one-line error, before a scene is loaded or a pixel
// rendered.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <string>

namespace hmb::cli {

// The file `path` (for option `option`, e.g. "--out") can be written: its extension is one of
// `extensions` (".png"), its folder exists or was made, and a file can be created there.
// Nothing to check when `path` is empty. Throws hmb::Error.
void prepareOutputFile(const std::string& path, std::initializer_list<const char*> extensions, const char* option);

// The folder `path` exists or was made, and a file can be created in it. Throws hmb::Error.
void prepareOutputFolder(const std::string& path, const char* option);

// The extension of `path`, lower case, with its dot (".exr").
std::string lowerExtension(const std::filesystem::path& path);

}  // namespace hmb::cli
