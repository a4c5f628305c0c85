#include "cpu_turns.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <utility>

#include <fmt/format.h>

#include "median.h"
#include "proc_stats.h"

namespace hubrt::bench {
namespace {

double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Keeps a stopped process stopped only as long as this lives: every way out of a turn continues it.
class Paused {
 public:
  static Expected<Paused> stop(const test_support::ChildProcess& child) {
    if (auto ok = child.signal(SIGSTOP); !ok) return std::move(ok).error();
    return Paused(child);
  }
  Paused(Paused&& other) noexcept : child_(std::exchange(other.child_, nullptr)) {}
  Paused(const Paused&) = delete;
  Paused& operator=(const Paused&) = delete;
  Paused& operator=(Paused&&) = delete;
  ~Paused() {
    if (child_ != nullptr) (void)child_->signal(SIGCONT);
  }

 private:
  explicit Paused(const test_support::ChildProcess& child) : child_(&child) {}
  const test_support::ChildProcess* child_;
};

// One turn: `other` stopped, `measured`'s CPU over opts.turn_s after opts.settle_s, in % of a core.
Expected<double> turn(const test_support::ChildProcess& measured, const test_support::ChildProcess& other,
                      const CpuTurnsOptions& opts, const std::function<void(double)>& idle) {
  auto paused = Paused::stop(other);
  if (!paused) {
    return make_error(ErrorCode::kUnavailable, fmt::format("cpu turns: {}", paused.error().message));
  }
  idle(opts.settle_s);
  auto before = read_proc(measured.pid());
  const double start = seconds_now();
  idle(opts.turn_s);
  auto after = read_proc(measured.pid());
  const double elapsed = seconds_now() - start;
  if (!before || !after) return make_error(ErrorCode::kUnavailable, "cpu turns: a process under test died");
  return cpu_percent(*before, *after, elapsed);
}

}  // namespace

Expected<CpuTurns> measure_cpu_in_turns(const test_support::ChildProcess& a,
                                        const test_support::ChildProcess& b, const CpuTurnsOptions& options,
                                        const std::function<void(double)>& idle) {
  CpuTurns out;
  for (int round = 0; round < options.rounds; ++round) {
    // Which goes first alternates, so neither is always the one measured right after the other ran.
    const bool a_first = round % 2 == 0;
    double a_pct = 0;
    double b_pct = 0;
    for (int i = 0; i < 2; ++i) {
      const bool measure_a = (i == 0) == a_first;
      auto pct = measure_a ? turn(a, b, options, idle) : turn(b, a, options, idle);
      if (!pct) return std::move(pct).error();
      (measure_a ? a_pct : b_pct) = *pct;
    }
    out.a_pct.push_back(a_pct);
    out.b_pct.push_back(b_pct);
    if (b_pct > 0) out.ratios.push_back(a_pct / b_pct);
  }
  if (!out.ratios.empty()) {
    out.median = median_of(out.ratios);
    out.min = *std::min_element(out.ratios.begin(), out.ratios.end());
    out.max = *std::max_element(out.ratios.begin(), out.ratios.end());
  }
  std::vector<double> changes;
  for (const auto* series : {&out.a_pct, &out.b_pct}) {
    for (std::size_t k = 1; k < series->size(); ++k) {
      if ((*series)[k - 1] > 0) changes.push_back(std::abs((*series)[k] / (*series)[k - 1] - 1));
    }
  }
  out.same_program_change = median_of(std::move(changes));
  return out;
}

}  // namespace hubrt::bench
