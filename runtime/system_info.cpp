#include "hmblur/system_info.h"

#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <thread>

#include "git_revision.h"  // generated at build time: HMB_GIT_REVISION
#ifndef HMB_VERSION
#define HMB_VERSION "unknown"
#endif

namespace hmb {
namespace {

std::string cpuModelName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0 || line.rfind("Model", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) {
        const auto start = line.find_first_not_of(" \t", colon + 1);
        if (start != std::string::npos) return line.substr(start);
      }
    }
  }
  return "unknown";
}

}  // namespace

SystemInfo querySystemInfo() {
  SystemInfo info;
  info.cpu = cpuModelName();
  info.hardwareThreads = std::thread::hardware_concurrency();
  const char* threads = std::getenv("LP_NUM_THREADS");
  info.lpNumThreads = threads ? threads : "unset";
  info.gitRevision = HMB_GIT_REVISION;
  info.version = HMB_VERSION;
  return info;
}

std::string utcTimestamp() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace hmb
