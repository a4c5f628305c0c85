// Tail figures that mean something on a noisy host (issue 33 point 1): a subject (the hub) and its
// baseline (the raw pong, the raw writer) measured in the same rounds, each round giving its own
// subject / baseline ratios of p95 and p99; what is judged is the median of the rounds' ratios,
// with their spread. A round where the baseline itself stalled (its p99 far above its usual) says
// the host was late, not the subject: its ratio comes out low (the baseline's tail is the host's
// stall), so it is shown as such and left out of the judged median, which can only make the
// subject look worse, never better.
#pragma once

#include <cstddef>
#include <vector>

namespace hubrt::bench {

// One round's tails of the subject and its baseline (any one unit).
struct RoundTails {
  double subject_p95 = 0;
  double subject_p99 = 0;
  double baseline_p95 = 0;
  double baseline_p99 = 0;
};

// Its samples, as nearest-rank percentiles (hubctl::summarize); 0 for an empty side.
RoundTails round_tails(const std::vector<double>& subject, const std::vector<double>& baseline);

// A baseline p99 more than this many times the median of the rounds' baseline p99 is a stall.
inline constexpr double kBaselineStallFactor = 3.0;

struct TailVerdict {
  std::vector<double> ratio_p95;  // one per round, in round order
  std::vector<double> ratio_p99;
  std::vector<bool> baseline_stalled;  // one per round
  std::size_t judged_rounds = 0;       // rounds without a stalled baseline
  // Over the judged rounds: median and spread (min, max) of the ratios.
  double median_p95 = 0;
  double median_p99 = 0;
  double min_p95 = 0;
  double max_p95 = 0;
  double min_p99 = 0;
  double max_p99 = 0;
};

// The verdict over `rounds`. A round whose baseline has a zero percentile gives a ratio of 0 and
// is not judged (nothing to compare with).
TailVerdict judge_tails(const std::vector<RoundTails>& rounds, double stall_factor = kBaselineStallFactor);

}  // namespace hubrt::bench
