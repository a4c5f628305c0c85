// The exit statuses of hubd and hubctl: one table, so that scripts and the systemd unit
// (RestartPreventExitStatus=2) read both programs the same way. `--help` of each program, the
// README ("Exit statuses") and packaging/deb/hubd.service.in repeat it; change them together.
#pragma once

#include <csignal>

namespace hubrt::exit_codes {

// Done: hubd stopped on request (SIGTERM, SIGINT) with its outputs safe; `--check` found the
// files good; a hubctl command did what it was asked (the check passed, something was received).
inline constexpr int kOk = 0;
// Runtime failure: a device or the network failed, the cycle failed; a hubctl check failed or
// nothing arrived. Restarting may help.
inline constexpr int kFailure = 1;
// Usage or configuration error: bad command line, a board or hub file that is missing or wrong,
// a hub the board cannot carry. Restarting cannot help (the unit's RestartPreventExitStatus=2).
inline constexpr int kUsage = 2;
// 128 + N: hubd stopped on signal N other than SIGTERM/SIGINT (SIGHUP: 129, SIGQUIT: 131,
// SIGUSR1: 138, ...) after driving its outputs to their safe levels. The same number a shell
// reports for a program killed by N, so scripts keep working; systemd counts it as a failure.
inline constexpr int kSignalBase = 128;

// hubd's exit status after it stopped on `signal`: kOk for the requested stops (SIGTERM,
// SIGINT), kSignalBase + signal for the others.
constexpr int for_stop_signal(int signal) noexcept {
  return signal == SIGTERM || signal == SIGINT ? kOk : kSignalBase + signal;
}

// The table as `--help` prints it (a CLI11 footer).
inline constexpr const char* kHelpFooter =
    "Exit status: 0 ok (stopped on SIGTERM/SIGINT, check passed); 1 runtime failure (device, network,\n"
    "check failed); 2 bad command line or configuration (restarting cannot help); 128+N: hubd stopped\n"
    "on signal N (SIGHUP 129, SIGQUIT 131, SIGUSR1 138, ...) after driving its outputs safe.";

}  // namespace hubrt::exit_codes
