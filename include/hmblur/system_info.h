// Facts about the host that every report and benchmark records.
#pragma once

#include <string>

namespace hmb {

struct SystemInfo {
  std::string cpu;             // model name
  unsigned hardwareThreads = 0;
  std::string lpNumThreads;    // LP_NUM_THREADS as set, or "unset"
  std::string gitRevision;     // revision the binary was built from
  std::string version;         // project version
};

SystemInfo querySystemInfo();

// Current UTC time as ISO 8601, for report headers.
std::string utcTimestamp();

}  // namespace hmb
