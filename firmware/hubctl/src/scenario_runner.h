// Runs a scenario against live hubs: sends commands the way the planner does (each node's
// command again and again at the scenario's rate until the node gets another), waits for States
// to meet conditions, acts on the simulated world, and reports every step.
#pragma once

#include <cstdio>
#include <memory>

#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"

#include "scenario.h"

namespace hubrt::hubctl {

struct PlayOptions {
  double rate_hz = 0.0;                                   // 0: the scenario's
  Duration discovery_timeout = std::chrono::seconds(10);  // to find a hub, node or the station
  int rounds = 1;                                         // 0: until stopped (Ctrl-C)
  bool quiet = false;                                     // report failures and the summary only
};

// Not thread-safe; one run at a time.
class ScenarioRunner {
 public:
  // `participant`, `scenario` and `out` must outlive the runner.
  ScenarioRunner(const dds::Participant& participant, const Scenario& scenario, PlayOptions options,
                 std::FILE* out);
  ~ScenarioRunner();
  ScenarioRunner(const ScenarioRunner&) = delete;
  ScenarioRunner& operator=(const ScenarioRunner&) = delete;

  // Runs the steps in order (all rounds), stopping at the first that fails or on Ctrl-C.
  // Returns true when every step passed. Each step is reported as it ends: PASS/FAIL, the time it
  // took, where it is in the file and what it does; a failed wait also shows what did not hold
  // and the last State received.
  bool run();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hubrt::hubctl
