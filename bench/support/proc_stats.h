// CPU time and memory of a process, read from /proc/<pid>/task/*/schedstat (or /proc/<pid>/stat)
// and /proc/<pid>/status (under qemu-user also /proc/<pid>/smaps: guest_memory.h).
#pragma once

#include <optional>

#include <sys/types.h>

#include "hubrt/base/status.h"

#include "guest_memory.h"

namespace hubrt::bench {

struct ProcSample {
  double cpu_s = 0;    // time its threads ran so far (user + system)
  double rss_mb = 0;   // resident set now (VmRSS)
  double anon_mb = 0;  // of it, anonymous pages (RssAnon; guest_memory.h says why it matters)
  double hwm_mb = 0;   // peak resident set (VmHWM)
  int threads = 0;
  // Under qemu-user: the guest program's own resident memory in MB, without qemu's
  // (guest_memory.h); none for a native process.
  std::optional<Resident> guest_mb;
};

// Errors: kNotFound when the process is gone; kIo when the files do not parse.
Expected<ProcSample> read_proc(pid_t pid);

// Time this machine's virtual CPUs were ready but not run because the hypervisor ran something
// else ("steal" in /proc/stat, proc(5)), summed over the CPUs, in seconds; 0 on bare metal. A
// window's difference says how long the whole machine stalled under the programs measured, which
// no scheduling policy inside it can prevent (the periods a SCHED_FIFO hub misses then).
double machine_steal_s();

// CPU use between two samples taken `elapsed_s` apart, in % of one core.
double cpu_percent(const ProcSample& before, const ProcSample& after, double elapsed_s) noexcept;

}  // namespace hubrt::bench
