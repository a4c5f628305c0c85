#include "proc_stats.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "guest_memory.h"

namespace hubrt::bench {
namespace {

// CPU time of every thread of `pid` so far, from /proc/<pid>/task/<tid>/schedstat (its first field
// is the time spent running, in ns: Documentation/scheduler/sched-stats.rst). /proc/<pid>/stat
// counts in clock ticks (10 ms here): over a 20 s window a hub at 1 % of a core is 20 ticks, +-1
// tick is +-5 % of the figure, too coarse for a ratio to a bare loop of about the same cost.
// nullopt when schedstat is missing (a kernel without CONFIG_SCHED_INFO).
std::optional<double> schedstat_cpu_s(pid_t pid) {
  std::error_code ec;
  double total_ns = 0;
  bool any = false;
  for (const auto& task : std::filesystem::directory_iterator(fmt::format("/proc/{}/task", pid), ec)) {
    std::ifstream schedstat(task.path() / "schedstat");
    double run_ns = 0;
    if (schedstat >> run_ns) {
      total_ns += run_ns;
      any = true;
    }
  }
  if (ec || !any) return std::nullopt;
  return total_ns * 1e-9;
}

}  // namespace

Expected<ProcSample> read_proc(pid_t pid) {
  ProcSample sample;
  std::ifstream stat(fmt::format("/proc/{}/stat", pid));
  std::string line;
  if (!stat || !std::getline(stat, line)) {
    return make_error(ErrorCode::kNotFound, fmt::format("process {} is gone", pid));
  }
  // The command name (field 2) may contain spaces; the fields after its ')' are fixed: utime and
  // stime are fields 14 and 15, i.e. the 12th and 13th after the state letter.
  const auto close = line.rfind(')');
  if (close == std::string::npos)
    return make_error(ErrorCode::kIo, fmt::format("/proc/{}/stat: no ')'", pid));
  std::istringstream rest(line.substr(close + 2));
  std::string field;
  unsigned long long utime = 0;
  unsigned long long stime = 0;
  for (int i = 3; i <= 15 && rest >> field; ++i) {
    if (i == 14) utime = std::stoull(field);
    if (i == 15) stime = std::stoull(field);
  }
  const auto ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  sample.cpu_s = schedstat_cpu_s(pid).value_or(static_cast<double>(utime + stime) / ticks);
  std::ifstream status(fmt::format("/proc/{}/status", pid));
  while (std::getline(status, line)) {
    std::istringstream fields(line);
    std::string key;
    double value = 0;
    fields >> key >> value;
    if (key == "VmRSS:") sample.rss_mb = value / 1024.0;
    if (key == "RssAnon:") sample.anon_mb = value / 1024.0;
    if (key == "VmHWM:") sample.hwm_mb = value / 1024.0;
    if (key == "Threads:") sample.threads = static_cast<int>(value);
  }
  sample.guest_mb = emulated_guest_rss_mb(pid);
  return sample;
}

double machine_steal_s() {
  std::ifstream stat("/proc/stat");
  std::string cpu;
  // "cpu user nice system idle iowait irq softirq steal ...", in clock ticks.
  unsigned long long fields[8] = {};
  stat >> cpu;
  for (auto& field : fields) stat >> field;
  if (!stat || cpu != "cpu") return 0;
  return static_cast<double>(fields[7]) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

double cpu_percent(const ProcSample& before, const ProcSample& after, double elapsed_s) noexcept {
  return elapsed_s > 0 ? (after.cpu_s - before.cpu_s) / elapsed_s * 100.0 : 0.0;
}

}  // namespace hubrt::bench
