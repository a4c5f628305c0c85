// Summaries of measured durations (periods, latencies): percentiles as an operator reads them.
#pragma once

#include <cstddef>
#include <vector>

namespace hubrt::hubctl {

struct Summary {
  std::size_t count = 0;
  double min = 0;
  double p50 = 0;
  double p90 = 0;
  double p95 = 0;
  double p99 = 0;
  double max = 0;
  double mean = 0;
};

// Nearest-rank percentiles of `values` (any unit). An empty input gives a zero Summary.
Summary summarize(std::vector<double> values);

}  // namespace hubrt::hubctl
