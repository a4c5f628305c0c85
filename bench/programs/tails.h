// The tails bench's rounds (bench/programs/tails.cc measures them, tails_report.cc judges and
// prints them).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "periodic_window.h"
#include "stage_attribution.h"

namespace hubrt::bench {

struct Options {
  std::string out = "tails.json";
  std::size_t rounds = 10;
  std::size_t sparse = 100;        // per side per round
  std::size_t back_to_back = 300;  // per side per round
  double hub_rate = 10;
  double heartbeat_rate = 100;
  double window_s = 5;  // 500 periods at 100 Hz: p99 is the 5th largest
};

// The round trips of one side in one regime: latencies (ms) and when each was sent (ns).
struct Samples {
  std::vector<double> ms;
  std::vector<TimedRoundTrip> timed;
  std::size_t lost = 0;
  void add(TimedRoundTrip t) {
    ms.push_back(static_cast<double>(t.echo - t.sent) * 1e-6);
    timed.push_back(t);
  }
};

// One planner's figures in one round: [regime][side], regime 0 sparse, 1 back to back; side 0 raw, 1 hub.
struct PlannerRound {
  Samples s[2][2];
};

struct Round {
  PlannerRound own;
  PlannerRound external;
  JitterWindow heartbeat;  // first: the hub, second: the raw writer
  std::vector<double> bare_ms;
  double steal_s = 0;
  double load = 0;
  std::string order;
};

// Judges the rounds against the aims, prints the tables on stdout, writes o.out.
// Returns the exit code: 0, or 1 when the result file cannot be written.
int report(const std::vector<Round>& rounds, const std::vector<TracedStep>& trace, const Options& o);

}  // namespace hubrt::bench
