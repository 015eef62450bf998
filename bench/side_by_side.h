// `hmblur-bench kernels --drivers A,B,...`: the same kernels on several drivers or devices in
// one run, side by side. hmblur-bench runs the kernels suite once per driver, each in a program
// of its own (a driver's libraries are chosen when a program starts, see driver_files.h), one
// after the other so that they do not compete for the CPU, and merges their reports here.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace hmb::bench {

struct DriverReport {
  std::string driver;      // as given to --drivers ("default": the environment's own driver)
  nlohmann::json report;   // that run's kernels report
};

// One report: each driver's device, system and cases, and per case the median time on every
// driver with its ratio to the first driver's.
nlohmann::json sideBySideJson(const std::vector<DriverReport>& runs, const std::string& command);
void writeSideBySideMarkdown(std::ostream& out, const nlohmann::json& sideBySide);
void writeSideBySideCsv(std::ostream& out, const nlohmann::json& sideBySide);

}  // namespace hmb::bench
