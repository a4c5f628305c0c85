// The median of a few figures (rounds' ratios): the mean of the middle two for an even count,
// unlike hubctl::summarize's nearest-rank p50, which picks one of them.
#pragma once

#include <algorithm>
#include <vector>

namespace hubrt::bench {

// 0 when empty.
inline double median_of(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  return values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
}

}  // namespace hubrt::bench
