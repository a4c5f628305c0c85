// hubd's last act when it crashes: drive its GPIO outputs to their safe levels from the handler
// of a fatal signal (SIGSEGV, SIGBUS, SIGILL, SIGFPE, SIGABRT) or from std::terminate, then die
// the way it would have died without the handler.
//
// Only async-signal-safe work happens there: the Linux GPIO backend's crash-safe table
// (hal/linux/crash_safe_outputs.h, its limits are listed there) and write(2) of a fixed line to
// stderr. Nothing for SIGKILL or the OOM killer (no handler runs; the unit's ExecStopPost
// `hubd --safe-outputs` does it), nothing on Modbus or CAN, nothing on the fake backend.
#pragma once

namespace hubrt::blackbox {
class BlackBox;
}

namespace hubrt::hubd {

// Installs the handlers, keeping the dispositions found (e.g. a sanitizer's): after driving the
// outputs, a handler puts the old disposition back and lets the signal take its course with it
// (a fault re-faults on return; a sent signal is raised again), and the terminate handler calls
// the terminate handler found. Call once, early, from the main thread. Not thread-safe.
void install_crash_handlers();

// After the outputs, a crash also writes `box` (BlackBox::crash_dump: async-signal-safe work only).
// Set once the black box is sealed, before the cycle runs; nullptr again before it is destroyed.
void set_crash_black_box(blackbox::BlackBox* box) noexcept;

}  // namespace hubrt::hubd
