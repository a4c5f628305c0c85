// CPU time and memory of a process, read from /proc/<pid>/task/*/schedstat (or /proc/<pid>/stat)
// and /proc/<pid>/status.
#pragma once

#include <sys/types.h>

#include "hubrt/base/status.h"

namespace hubrt::bench {

struct ProcSample {
  double cpu_s = 0;   // time its threads ran so far (user + system)
  double rss_mb = 0;  // resident set now (VmRSS)
  double hwm_mb = 0;  // peak resident set (VmHWM)
  int threads = 0;
};

// Errors: kNotFound when the process is gone; kIo when the files do not parse.
Expected<ProcSample> read_proc(pid_t pid);

// CPU use between two samples taken `elapsed_s` apart, in % of one core.
double cpu_percent(const ProcSample& before, const ProcSample& after, double elapsed_s) noexcept;

}  // namespace hubrt::bench
