// bench/support/cpu_turns: while one process is measured the other is stopped, both run again
// afterwards (also when a turn fails), and the figures tell a busy process from an idle one.
#include "cpu_turns.h"

#include <unistd.h>

#include <chrono>
#include <csignal>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"

#include "median.h"

namespace hubrt::bench {
namespace {

using test_support::ChildProcess;

// The state letter of /proc/<pid>/stat: 'T' stopped, 'R'/'S' running or sleeping.
char state_of(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  return close == std::string::npos || close + 2 >= text.size() ? '?' : text[close + 2];
}

// Whether `holds` becomes true within 2 s, looked at every 10 ms.
template <class Predicate>
bool eventually(Predicate holds) {
  for (int i = 0; i < 200; ++i) {
    if (holds()) return true;
    ::usleep(10'000);
  }
  return holds();
}

ChildProcess start_shell(const std::string& script) {
  auto child = ChildProcess::start("/bin/sh", {"-c", script});
  EXPECT_TRUE(child.is_ok());
  return std::move(*child);
}

TEST(CpuTurns, OneIsStoppedWhileTheOtherIsMeasuredAndBothRunAfter) {
  const ChildProcess busy = start_shell("while :; do :; done");
  const ChildProcess idle_process = start_shell("exec sleep 600");
  int calls = 0;
  int calls_with_one_stopped = 0;
  const CpuTurnsOptions options{.rounds = 2, .turn_s = 0.3, .settle_s = 0.1};
  // The idle one first: its ratio to the busy one is defined (the other way round it divides by 0).
  auto turns = measure_cpu_in_turns(idle_process, busy, options, [&](double seconds) {
    ++calls;
    // The stop is asynchronous: the state reads 'T' once the process has taken the signal, which
    // a process waiting for a core on a loaded machine does only when it runs: up to 2 s.
    if (eventually([&] { return (state_of(busy.pid()) == 'T') != (state_of(idle_process.pid()) == 'T'); }))
      ++calls_with_one_stopped;
    ::usleep(static_cast<useconds_t>(seconds * 1e6));
  });
  ASSERT_TRUE(turns.is_ok()) << turns.error().message;
  EXPECT_EQ(calls, 2 * 2 * 2);  // 2 rounds x 2 turns x (settle, measure)
  EXPECT_EQ(calls_with_one_stopped, calls);
  EXPECT_TRUE(eventually([&] { return state_of(busy.pid()) != 'T'; }));
  EXPECT_TRUE(eventually([&] { return state_of(idle_process.pid()) != 'T'; }));
  ASSERT_EQ(turns->ratios.size(), 2U);
  // The busy loop takes a core while the test runs alone, and a tenth of one even beside the
  // other tests of the default suite (4 at a time on 2 cores, each with threads of its own); the
  // sleeping process takes next to nothing.
  for (const double pct : turns->a_pct) EXPECT_LT(pct, 5.0);
  for (const double pct : turns->b_pct) EXPECT_GT(pct, 10.0);
  EXPECT_LT(turns->median, 0.1);
  EXPECT_LE(turns->min, turns->median);
  EXPECT_GE(turns->max, turns->median);
  (void)busy.signal(SIGKILL);
  (void)idle_process.signal(SIGKILL);
}

TEST(CpuTurns, AProcessGoneIsAnErrorAndTheOtherRunsAgain) {
  ChildProcess gone = start_shell("exit 0");
  ASSERT_TRUE(gone.wait(std::chrono::seconds(10)).is_ok());  // reaped: cannot be stopped
  const ChildProcess running = start_shell("exec sleep 600");
  const CpuTurnsOptions options{.rounds = 1, .turn_s = 0.1, .settle_s = 0.05};
  auto turns = measure_cpu_in_turns(running, gone, options,
                                    [](double seconds) { ::usleep(static_cast<useconds_t>(seconds * 1e6)); });
  ASSERT_FALSE(turns.is_ok());
  EXPECT_NE(turns.error().message.find("cpu turns"), std::string::npos) << turns.error().message;
  ::usleep(20'000);
  EXPECT_NE(state_of(running.pid()), 'T');
  (void)running.signal(SIGKILL);
}

TEST(CpuTurns, MedianOfAnEvenCountIsTheMeanOfTheMiddleTwo) {
  EXPECT_DOUBLE_EQ(median_of({3.0, 1.0, 2.0, 10.0}), 2.5);
  EXPECT_DOUBLE_EQ(median_of({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(median_of({}), 0.0);
}

}  // namespace
}  // namespace hubrt::bench
