// A hub started by `hubctl conformance --launch "CMD"`, so that the suite can time the hub's start
// to its first State. The command runs through /bin/sh (`exec CMD`, so the PID is the hub's); its
// output goes to hubctl's stderr, leaving stdout to the report.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <sys/types.h>

#include "hubrt/base/status.h"

namespace hubrt::hubctl {

// Move-only. The destructor stops a hub still running (SIGTERM, then SIGKILL after 5 s) and reaps
// it. Thread-safety: none.
class LaunchedHub {
 public:
  // Starts `command` with the current environment plus `extra_env`. Returns at once; the steady
  // time of the start is started_at_s(). Errors: kIo when the shell cannot be spawned.
  static Expected<LaunchedHub> start(const std::string& command,
                                     const std::vector<std::pair<std::string, std::string>>& extra_env);

  ~LaunchedHub();
  LaunchedHub(LaunchedHub&& other) noexcept;
  LaunchedHub& operator=(LaunchedHub&&) = delete;
  LaunchedHub(const LaunchedHub&) = delete;
  LaunchedHub& operator=(const LaunchedHub&) = delete;

  [[nodiscard]] double started_at_s() const noexcept { return started_at_s_; }
  [[nodiscard]] pid_t pid() const noexcept { return pid_; }
  // Non-empty ("exit code 2", "killed by signal 9") once the hub ended on its own.
  [[nodiscard]] std::string ended() noexcept;
  // SIGTERM, then SIGKILL if it has not ended after `grace_s`; reaps it. Returns how it ended.
  std::string stop(double grace_s = 5.0) noexcept;

 private:
  LaunchedHub(pid_t pid, double started_at_s) noexcept : pid_(pid), started_at_s_(started_at_s) {}
  pid_t pid_ = -1;  // -1 once reaped
  double started_at_s_ = 0;
  std::string end_;
};

}  // namespace hubrt::hubctl
