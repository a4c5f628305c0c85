// Driving the process's GPIO outputs to their safe levels from a crash handler (a fatal signal or
// std::terminate), where nothing but async-signal-safe work is allowed.
//
// Every output open_gpiod_output() requests is entered, at open, in a fixed table of this
// process: the line request's file descriptor, its safe level and polarity. The table is
// lock-free (atomics only, no allocation), so a signal handler may walk it at any moment,
// including while another thread opens or closes an output. An output leaves the table before
// its descriptor is closed, so the handler never writes to a descriptor that has been reused.
//
// What drive_outputs_safe_from_crash() cannot do (see docs/deploy.md, "Safe outputs after any
// stop"):
// - nothing for SIGKILL, the OOM killer or a power loss: no handler runs. The systemd unit's
//   ExecStopPost (`hubd --safe-outputs`) covers those;
// - nothing on the fake backend (its "lines" are the dying process's memory) and nothing on
//   Modbus or CAN: a bus exchange is neither async-signal-safe nor bounded here (the lift drive
//   stops itself through its communication watchdog);
// - a process whose memory is corrupted may have a corrupted table: each entry carries a check
//   word and a mismatching entry is skipped, which catches a stray write, not every corruption;
// - more than kCrashSafeCapacity outputs at once: the others work but are not in the table.
#pragma once

#include <cstddef>

namespace hubrt::hal {

// Outputs the table holds at once; a hub has a handful.
inline constexpr std::size_t kCrashSafeCapacity = 64;

struct CrashSafeResult {
  int driven = 0;  // outputs whose safe level was written
  int failed = 0;  // outputs whose write the kernel refused (e.g. the chip went away)
};

// Writes the safe level to every output in the table (GPIOHANDLE_SET_LINE_VALUES_IOCTL), then,
// where the kernel supports it (Linux 5.5+, GPIOHANDLE_SET_CONFIG_IOCTL), also sets the line's
// bias toward that level, so that the line stays there after the dying process releases it on
// drivers that keep the bias (gpio-sim; the Raspberry Pi's pinctrl, which turns a released line
// into an input with its pull). Async-signal-safe: atomics and ioctl(2) only; preserves errno.
// May run concurrently with itself (two crashing threads): the writes are idempotent.
CrashSafeResult drive_outputs_safe_from_crash() noexcept;

// How many outputs the table holds now (tests, diagnostics). Thread-safe.
std::size_t crash_safe_output_count() noexcept;

}  // namespace hubrt::hal
