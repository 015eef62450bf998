#include "bench/side_by_side.h"

#include <iomanip>
#include <map>
#include <sstream>
#include <tuple>

#include "hmblur/error.h"
#include "hmblur/report.h"

namespace hmb::bench {
namespace {

using CaseKey = std::tuple<std::string, uint32_t, uint32_t, uint32_t, uint32_t>;

CaseKey keyOf(const nlohmann::json& c) {
  return {c.at("kernel"), c.at("width"), c.at("height"), c.at("triangles"), c.at("rays")};
}

// "llvmpipe (LLVM 15.0.6, 256 bits), Mesa 25.0.7 (LLVM 15.0.6)": what a column is named after.
std::string label(const nlohmann::json& device) {
  return device.value("name", std::string("?")) + ", " + device.value("driver_info", std::string("?"));
}

std::string sizeText(const nlohmann::json& c) {
  std::ostringstream s;
  if (c.at("width").get<uint32_t>() > 0) s << c.at("width").get<uint32_t>() << "x" << c.at("height").get<uint32_t>();
  if (c.at("triangles").get<uint32_t>() > 0) s << (s.tellp() > 0 ? ", " : "") << c.at("triangles") << " tris";
  if (c.at("rays").get<uint32_t>() > 0) s << (s.tellp() > 0 ? ", " : "") << c.at("rays") << " rays";
  return s.str();
}

}  // namespace

nlohmann::json sideBySideJson(const std::vector<DriverReport>& runs, const std::string& command) {
  if (runs.empty()) throw Error("--drivers: no driver ran");
  nlohmann::json out = {{"suite", "kernels"},
                        {"what", "device time of single kernels on synthetic inputs, the same cases on several "
                                 "drivers or devices, one after the other in one run"},
                        {"command", command},
                        {"date", utcTimestamp()},
                        {"settings", runs.front().report.at("settings")},
                        {"drivers", nlohmann::json::array()},
                        {"cases", nlohmann::json::array()}};
  for (const DriverReport& run : runs)
    out["drivers"].push_back({{"driver", run.driver},
                              {"device", run.report.at("device")},
                              {"system", run.report.at("system")},
                              {"other_cpu_load_cores", run.report.value("other_cpu_load_cores", nlohmann::json())},
                              {"cases", run.report.at("cases")}});
  // Cases in the first driver's order; every driver ran the same list.
  std::vector<std::map<CaseKey, nlohmann::json>> byKey(runs.size());
  for (size_t d = 0; d < runs.size(); ++d)
    for (const nlohmann::json& c : runs[d].report.at("cases")) byKey[d][keyOf(c)] = c;
  for (const nlohmann::json& first : runs.front().report.at("cases")) {
    nlohmann::json row = {{"kernel", first.at("kernel")},
                          {"width", first.at("width")},
                          {"height", first.at("height")},
                          {"triangles", first.at("triangles")},
                          {"rays", first.at("rays")},
                          {"median_ms", nlohmann::json::array()},
                          {"over_first", nlohmann::json::array()}};
    const double base = first.at("ms").at("median").get<double>();
    for (size_t d = 0; d < runs.size(); ++d) {
      const auto found = byKey[d].find(keyOf(first));
      if (found == byKey[d].end()) throw Error("--drivers: driver " + runs[d].driver + " did not run every case");
      const double ms = found->second.at("ms").at("median").get<double>();
      row["median_ms"].push_back(ms);
      row["over_first"].push_back(ms / base);
    }
    out["cases"].push_back(row);
  }
  return out;
}

void writeSideBySideMarkdown(std::ostream& out, const nlohmann::json& s) {
  const nlohmann::json& drivers = s.at("drivers");
  out << "# Kernels side by side\n\nMedian device time (timestamp queries) of each kernel on each driver, run one "
         "after the other in one command: `"
      << s.at("command").get<std::string>() << "`. CPU " << drivers.at(0).at("system").value("cpu", "?")
      << ", LP_NUM_THREADS " << drivers.at(0).at("system").value("LP_NUM_THREADS", "?") << ", revision "
      << drivers.at(0).at("system").value("git_revision", "?") << ".\n\n";
  for (size_t d = 0; d < drivers.size(); ++d)
    out << "- driver " << d + 1 << ": " << label(drivers[d].at("device")) << " (--drivers "
        << drivers[d].at("driver").get<std::string>() << ")\n";
  out << "\n| kernel | input |";
  for (size_t d = 0; d < drivers.size(); ++d) out << " driver " << d + 1 << " ms |";
  for (size_t d = 1; d < drivers.size(); ++d) out << " driver " << d + 1 << " / 1 |";
  out << "\n|---|---|";
  for (size_t d = 0; d < 2 * drivers.size() - 1; ++d) out << "---:|";
  out << "\n" << std::fixed;
  for (const nlohmann::json& c : s.at("cases")) {
    out << "| " << c.at("kernel").get<std::string>() << " | " << sizeText(c) << " |";
    for (const nlohmann::json& ms : c.at("median_ms")) out << " " << std::setprecision(2) << ms.get<double>() << " |";
    for (size_t d = 1; d < drivers.size(); ++d)
      out << " " << std::setprecision(2) << c.at("over_first").at(d).get<double>() << "x |";
    out << "\n";
  }
}

void writeSideBySideCsv(std::ostream& out, const nlohmann::json& s) {
  out << "kernel,width,height,triangles,rays";
  for (size_t d = 0; d < s.at("drivers").size(); ++d) out << ",driver" << d + 1 << "_median_ms";
  out << "\n";
  for (const nlohmann::json& c : s.at("cases")) {
    out << c.at("kernel").get<std::string>() << ',' << c.at("width") << ',' << c.at("height") << ','
        << c.at("triangles") << ',' << c.at("rays");
    for (const nlohmann::json& ms : c.at("median_ms")) out << ',' << ms.get<double>();
    out << "\n";
  }
}

}  // namespace hmb::bench
