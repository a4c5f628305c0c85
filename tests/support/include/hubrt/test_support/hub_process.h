// A hubd started by a test in the test's own DDS domain on loopback (HubUnderTest,
// hub_under_test.h, adds the planner and the State readers around it).
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::test_support {

struct HubProcessOptions {
  std::string board = "host-sim";
  std::string hub = "dock_ecu";
  std::vector<std::string> extra_args{};  // (initialised: GCC checks designated initialisers' omissions)
  Environment extra_env{};
  // kClosedPipe: stdout and stderr lead nowhere (`hubd | head -0`); start() then cannot wait for
  // "running hub" and returns once hubd is spawned.
  OutputMode output = OutputMode::kFiles;
  // How long start() waits for "running hub": start-up under sanitizers on a loaded 2-core
  // machine takes seconds. HubUnderTest waits the longer of this and its own patience.
  Duration start_patience = std::chrono::seconds(20);
};

class HubProcess {
 public:
  // Starts hubd and waits (up to options.start_patience) until it says it runs. Errors carry
  // hubd's output and what it was doing when the wait gave up (ChildProcess::activity).
  // The hubd started is this build's, or the program HUBRT_TEST_HUBD names (a hubd built elsewhere
  // with other hub types: the new-hub check, tests/new_hub).
  static Expected<HubProcess> start(const TestDomain& domain, const HubProcessOptions& options);

  ChildProcess& process() { return process_; }
  // hubd's output so far, for failure messages.
  std::string output() const { return process_.stdout_text() + process_.stderr_text(); }

 private:
  explicit HubProcess(ChildProcess process) : process_(std::move(process)) {}
  ChildProcess process_;
};

// Runs hubd to completion with `args` (for configuration errors); returns exit status and output.
// HUBRT_CONFIG_DIR is config_dir() unless `extra_env` sets it.
struct Finished {
  ExitStatus status;
  std::string output;
};
Expected<Finished> run_hubd(const TestDomain& domain, const std::vector<std::string>& args, Duration timeout,
                            const Environment& extra_env = {});

// The hubd the tests start: HUBRT_TEST_HUBD when set, else this build's.
std::string hubd_path();
// Where hubd and hubctl find boards/ and hubs/<hub>/ by name (their HUBRT_CONFIG_DIR):
// HUBRT_TEST_CONFIG_DIR when set, else this source tree. The two variables let a hub folder's tests
// run against a hubd and a tree built elsewhere (the new-hub check, tests/new_hub).
std::string config_dir();

}  // namespace hubrt::test_support
