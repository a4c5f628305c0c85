// A hubd started by a test in the test's own DDS domain on loopback, plus a DDS participant for
// the test to talk to it.
#pragma once

#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/dds/participant.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::integration {

struct HubProcessOptions {
  std::string board = "host-sim";
  std::string hub = "dock_ecu";
  std::vector<std::string> extra_args;
  test_support::Environment extra_env;
};

class HubProcess {
 public:
  // Starts hubd and waits (up to 20 s: start-up under sanitizers on a loaded 2-core machine is
  // slow) until it says it runs. Errors carry hubd's output.
  static Expected<HubProcess> start(const test_support::TestDomain& domain, const HubProcessOptions& options);

  test_support::ChildProcess& process() { return process_; }
  // hubd's output so far, for failure messages.
  std::string output() const { return process_.stdout_text() + process_.stderr_text(); }

 private:
  explicit HubProcess(test_support::ChildProcess process) : process_(std::move(process)) {}
  test_support::ChildProcess process_;
};

// Runs hubd to completion with `args` (for configuration errors); returns exit status and output.
// HUBRT_CONFIG_DIR is the source tree unless `extra_env` sets it.
struct Finished {
  test_support::ExitStatus status;
  std::string output;
};
Expected<Finished> run_hubd(const test_support::TestDomain& domain, const std::vector<std::string>& args,
                            Duration timeout, const test_support::Environment& extra_env = {});

}  // namespace hubrt::integration
