// Runs a scenario against live hubs: sends commands the way the planner does (each node's
// command again and again at the scenario's rate until the node gets another), waits for States
// to meet conditions, acts on the simulated world, and reports every step.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>

#include "hubrt/base/time.h"
#include "hubrt/dds/participant.h"

#include "scenario.h"

namespace hubrt::hubctl {

struct PlayOptions {
  double rate_hz = 0.0;                                   // 0: the scenario's
  Duration discovery_timeout = std::chrono::seconds(10);  // to find a hub, node or the station
  int rounds = 1;                                         // 0: until stopped (Ctrl-C)
  bool quiet = false;                                     // report failures and the summary only
  std::uint32_t command_lifespan_ms = 1000;               // LIFESPAN of the commands (0: none)
  std::string ros_namespace;                              // the station's ("" or "/cell_a"; docs/plant.md)
};

enum class PlayOutcome : std::uint8_t {
  kPassed,       // every step of every round passed
  kFailed,       // a step failed (its report says why)
  kInterrupted,  // SIGINT/SIGTERM (stop_requested) stopped the run before it was done
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

  // Runs the steps in order (all rounds), stopping at the first that fails or on Ctrl-C. Each
  // step is reported as it ends: PASS/FAIL, the time it took, where it is in the file and what it
  // does; a failed wait also shows what did not hold and the last State received. A step cut
  // short by Ctrl-C is reported as STOP, never as a failed wait, and the run ends with
  // "play: interrupted at step ..." (kInterrupted), also with --rounds 0.
  PlayOutcome run();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hubrt::hubctl
