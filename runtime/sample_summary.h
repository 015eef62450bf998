// Median and spread of a quantity measured several times (a frame's or a pass's device time):
// what the benchmarks and `hmblur render --repeat` report.
#pragma once

#include <vector>

#include <nlohmann/json.hpp>

namespace hmb {

struct Summary {
  double median = 0, min = 0, max = 0, q1 = 0, q3 = 0;  // q1/q3: the interquartile range
  std::vector<double> samples;                         // in measurement order
};

// Quantiles interpolate linearly between the sorted samples; no samples, all zero.
Summary summarize(std::vector<double> samples);
// Its JSON: median, min, max, q1, q3 and every sample.
nlohmann::json summaryJson(const Summary& s);

}  // namespace hmb
