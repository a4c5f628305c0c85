// CPU of two processes measured in turns: while one is measured the other is stopped (SIGSTOP), so
// neither's wake-ups, caches or core are shared with the other's during its own measurement.
//
// Why (issue 16, point 4): side by side on a 2-core machine, the CPU one periodic process takes per
// wake-up depends on how its wake-ups interleave with the other's and with their subscribers'. For
// the same two programs, fresh pairs measured side by side for 10 s gave hub / bare loop ratios from
// 0.81 to 1.55 (2026-11-28): the arrangement, not the programs. In turns each process runs with only
// its own subscriber, and the turns alternate, so slow drifts of the machine fall on both alike. The
// figure kept is the median of the rounds' ratios; the same program's change from one turn to its
// next says how far a single turn can be trusted (the noise of the measurement itself).
#pragma once

#include <functional>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/test_support/child_process.h"

namespace hubrt::bench {

struct CpuTurnsOptions {
  int rounds = 8;         // each round: one turn of A, one of B (which goes first alternates)
  double turn_s = 2.0;    // how long each turn is measured
  double settle_s = 0.3;  // after the other stopped, before measuring (a resumed bare loop
                          // catches up its missed deadlines in a burst: not in the other's turn)
};

struct CpuTurns {
  std::vector<double> a_pct;   // CPU in % of one core, per turn of A
  std::vector<double> b_pct;   // and of B, in the same rounds
  std::vector<double> ratios;  // A / B per round
  double median = 0;           // of `ratios`
  double min = 0;
  double max = 0;
  // The median over both programs of |x(turn k+1) / x(turn k) - 1|: how much one program's own
  // figure moves between two of its turns in this run.
  double same_program_change = 0;
};

// Measures `a` and `b` in turns. `idle(seconds)` must keep the caller's own duties (draining its
// readers) for that long. Both processes are running again when this returns, error or not.
// Errors: kUnavailable when a process died or could not be stopped or continued.
Expected<CpuTurns> measure_cpu_in_turns(const test_support::ChildProcess& a,
                                        const test_support::ChildProcess& b, const CpuTurnsOptions& options,
                                        const std::function<void(double)>& idle);

}  // namespace hubrt::bench
