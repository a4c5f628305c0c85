#include "tail_rounds.h"

#include <algorithm>

#include "median.h"
#include "stats.h"

namespace hubrt::bench {

RoundTails round_tails(const std::vector<double>& subject, const std::vector<double>& baseline) {
  const hubctl::Summary s = hubctl::summarize(subject);
  const hubctl::Summary b = hubctl::summarize(baseline);
  return {s.p95, s.p99, b.p95, b.p99};
}

TailVerdict judge_tails(const std::vector<RoundTails>& rounds, double stall_factor) {
  TailVerdict v;
  std::vector<double> baseline_p99;
  for (const RoundTails& r : rounds) {
    if (r.baseline_p99 > 0) baseline_p99.push_back(r.baseline_p99);
  }
  const double usual = median_of(baseline_p99);
  std::vector<double> judged_p95;
  std::vector<double> judged_p99;
  for (const RoundTails& r : rounds) {
    const bool comparable = r.baseline_p95 > 0 && r.baseline_p99 > 0;
    const double p95 = comparable ? r.subject_p95 / r.baseline_p95 : 0.0;
    const double p99 = comparable ? r.subject_p99 / r.baseline_p99 : 0.0;
    const bool stalled = comparable && r.baseline_p99 > stall_factor * usual;
    v.ratio_p95.push_back(p95);
    v.ratio_p99.push_back(p99);
    v.baseline_stalled.push_back(stalled);
    if (comparable && !stalled) {
      judged_p95.push_back(p95);
      judged_p99.push_back(p99);
    }
  }
  v.judged_rounds = judged_p95.size();
  if (v.judged_rounds == 0) return v;
  v.median_p95 = median_of(judged_p95);
  v.median_p99 = median_of(judged_p99);
  const auto [lo95, hi95] = std::minmax_element(judged_p95.begin(), judged_p95.end());
  const auto [lo99, hi99] = std::minmax_element(judged_p99.begin(), judged_p99.end());
  v.min_p95 = *lo95;
  v.max_p95 = *hi95;
  v.min_p99 = *lo99;
  v.max_p99 = *hi99;
  return v;
}

}  // namespace hubrt::bench
