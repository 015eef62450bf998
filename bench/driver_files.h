// --driver-files: a suite run on a Vulkan driver that is unpacked rather than installed, such
// as the Mesa 25 lavapipe that scripts/mesa25-lavapipe.sh unpacks into the build folder. The
// loader takes the driver from VK_DRIVER_FILES; the driver's own libraries (its libdrm) are
// found through LD_LIBRARY_PATH, which the dynamic linker reads only when a program starts, so
// hmblur-bench starts itself again with both set.
#pragma once

#include <string>

namespace hmb::bench {

struct DriverFiles {
  std::string manifests;     // VK_DRIVER_FILES: the ICD manifests, ':' separated
  std::string libraryPaths;  // the folders of their libraries, ':' separated
  std::string shaderCache;   // a shader-cache folder of this driver's own, unless MESA_SHADER_CACHE_DIR is set
};

// PATH is an ICD manifest (.json), a folder of manifests, or a folder with
// usr/share/vulkan/icd.d inside (what scripts/mesa25-lavapipe.sh makes). Throws hmb::Error
// with one line when it names no manifest, or a manifest whose library is missing.
DriverFiles resolveDriverFiles(const std::string& path);

// Returns when this process already runs on the driver at `path`; otherwise starts this
// program again, with the same arguments, on that driver, and does not return (throws
// hmb::Error if it cannot).
void runOnDriverFiles(const std::string& path, char** argv);

}  // namespace hmb::bench
