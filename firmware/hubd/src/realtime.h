// `hubd --realtime`: the process's threads run under SCHED_FIFO at a configured priority and its
// memory is locked (mlockall), so that at 1 kHz neither an ordinary process nor a page fault
// delays a cycle past its period. Where the system does not permit it (no CAP_SYS_NICE and an
// RLIMIT_RTPRIO below the priority; no CAP_IPC_LOCK and an RLIMIT_MEMLOCK too small to lock
// everything) hubd refuses to start rather than run without what was asked for.
#pragma once

#include <cstddef>

#include "hubrt/base/status.h"

namespace hubrt::hubd {

// The default priority: above every ordinary process and the kernel's threaded interrupt
// handlers' default (50) stays above it, so a device's interrupts are still served first.
inline constexpr int kDefaultRealtimePriority = 40;

// The stack of each thread started after enter_realtime() (all of it locked, so resident).
inline constexpr std::size_t kRealtimeThreadStackBytes = std::size_t{1} << 20;

// Puts the calling thread under SCHED_FIFO at `priority` (1..99), then locks the process's
// current and future memory. Call it before any other thread exists: threads created afterwards
// (Cyclone's receive and event threads, a Modbus worker) inherit the policy, so that a command
// is received as promptly as the cycle runs. The kernel's RT throttling (sched_rt_runtime_us)
// still leaves ordinary processes 5 % of each CPU.
// Errors: kPermissionDenied naming what is missing (CAP_SYS_NICE or LimitRTPRIO=, CAP_IPC_LOCK or
// LimitMEMLOCK=) and the system call's message; kInvalidArgument for a priority outside 1..99.
// On an error the scheduling policy is left as it was. Also makes 1 MiB the default stack of
// threads started afterwards (kRealtimeThreadStackBytes), since locked stacks are resident.
Expected<void> enter_realtime(int priority);

}  // namespace hubrt::hubd
