// Issue 16, point 1: a hub allocates nothing per steady-state cycle in its whole process (every
// thread: the cycle's and Cyclone's receive, delivery, timed-event and gc threads, the black box's),
// with its black box recording every command and State (issue 30), with the real
// assembly (board + hub file, fake backend with its sim bridge, real State types, real DDS writers,
// /diagnostics), a subscriber in another process (hubctl echo, which also shows the State still
// decodes) and a planner in another process repeating one command at 100 Hz (hubctl send).
// Allocations are counted by hubrt_alloc_counter (the sanitizer's allocation hooks in the ASan and
// TSan builds, an interposed malloc otherwise).
//
// What remains is not per cycle but per lease period, and Cyclone 0.10.2 cannot be configured out
// of it without weakening the lease (traced with gdb over a build of Cyclone 0.10.2's source,
// docs/benchmarks.md "Heap allocations"): every participant announces itself every 0.8 x its lease
// (Discovery/LeaseDuration, 10 s: every 8 s) with an SPDP sample and a participant-message (PMD)
// sample, and each allocates where it is made and where it is received:
// - on Cyclone's timed-event thread "tev", for this participant: the SPDP resend builds its key as
//   a serdata (q_xevent.c resend_spdp_sample_by_guid_key: ddsi_serdata_from_sample) and queues it
//   (qxev_msg: a struct xevent_nt per message), 2; write_pmd_message (ddsi_pmd.c:81:
//   ddsi_serdata_from_sample of the PMD pserop type) 3: kOwnAnnouncementAllocations;
// - on its discovery delivery thread "dq.builtins", for every SPDP received (the two peers' and
//   our own, which the unicast loopback peer list sends us too): serdata_plist_new and the
//   parameter list's deserialisation (ddsi_plist_init_frommsg: a string and two locators), 4; for
//   every PMD received (the peers'), serdata_pserop_new twice, 2.
// Both are the lease at work (a peer renews our lease at its end from them; a hub killed without
// a goodbye is dropped by the station after the lease), whatever the hub's rate: at 1 kHz 0.0026
// allocations per cycle, at 100 Hz 0.026. So: those two threads at most one announcement of each
// participant per window (the window, 1 s, is shorter than the 8 s between announcements), and a
// window clear of announcements has 0 in the whole process, every thread included.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/assembly/hub_assembly.h"
#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

#include "alloc_counter.h"
#include "assembled_sim_dock.h"

namespace hubrt {
namespace {

using std::chrono::seconds;

constexpr std::int64_t kPeriodNs = 1'000'000;  // the hub's rate: 1 kHz
// Warm-up: Cyclone's first samples, the pools growing to what Cyclone holds at once, the first
// /diagnostics (once a second), the planner's first commands, and Cyclone's answers to the peers'
// discovery: each newly discovered participant gets our SPDP sent to it 4 times, 1 s apart
// (q_xevent.c handle_xevk_spdp, "directed"), each allocating as a resend does.
constexpr int kWarmupCycles = 4500;
// Lease-driven allocations per announcement (see above); two peers (hubctl echo and send). On the
// timed-event thread, once each after start-up and seen in a window: the PMD writer's history
// growing (whc_default_insert_seq, its hash resized), 2, and a writer deleted with samples not yet
// acknowledged, deleted for good after Cyclone's linger (handle_xevk_delete_writer: a built-in
// topic sample and a gc request), 2.
constexpr std::uint64_t kOwnAnnouncementAllocations = 5;
constexpr std::uint64_t kTimedEventOneOffs = 4;
constexpr std::uint64_t kPeers = 2;
constexpr std::uint64_t kReceivedAnnouncementsAllocations = (kPeers + 1) * 4 + kPeers * 2;
constexpr int kMeasuredCycles = 1000;
// Process start and discovery in sanitizer builds on a loaded 2-core machine; only reached when
// something is broken.
constexpr auto kStartBound = seconds(60);

void sleep_until_next(timespec& next) {
  next.tv_nsec += kPeriodNs;
  if (next.tv_nsec >= 1'000'000'000) {
    next.tv_nsec -= 1'000'000'000;
    ++next.tv_sec;
  }
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr) == EINTR) {
  }
}

TEST(HubProcessAllocations, NoneInSteadyStateWithSubscriberAndPlannerInOtherProcesses) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  SystemClock clock;
  auto assembled = integration::assemble_sim_dock(*domain, clock, 1000);
  ASSERT_TRUE(assembled) << assembled.error().message;
  runtime::Hub& hub = *(*assembled)->hub;

  auto echo = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, {"echo", "/dock_ecu/dock/state", "--json"},
                                                domain->env());
  ASSERT_TRUE(echo) << echo.error().message;
  auto planner =
      test_support::ChildProcess::start(HUBRT_HUBCTL_PATH,
                                        {"send", "/dock/command", "target_type=dock", "target_name=dock",
                                         "action=monitor", "--rate", "100", "-q"},
                                        domain->env());
  ASSERT_TRUE(planner) << planner.error().message;

  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  const auto run = [&](int cycles) {
    for (int i = 0; i < cycles; ++i) {
      hub.cycle(clock.now());
      sleep_until_next(next);
    }
  };
  // Until the subscriber decodes the hub's State (the command's action echoed in it) and the
  // planner's commands are in force.
  const auto deadline = std::chrono::steady_clock::now() + kStartBound;
  while (!echo->wait_for_output("\"monitor\"", std::chrono::milliseconds(0)) &&
         std::chrono::steady_clock::now() < deadline) {
    run(100);
  }
  ASSERT_TRUE(echo->wait_for_output("\"monitor\"", std::chrono::milliseconds(0)))
      << "hubctl echo never showed a State echoing the planner's command: " << echo->stderr_text();
  run(kWarmupCycles);

  hubrt::testing::count_allocations_of_threads_named({"tev", "dq.builtins"});
  // Steady state means Cyclone's own freelists (writer history nodes, messages) and the write pool
  // have reached what this load needs; a burst of scheduling delay on a loaded machine can raise
  // that high-water mark once more (on the cycle thread). Windows of kMeasuredCycles are measured
  // until one has no allocation anywhere in the process; 8 windows span a whole announcement
  // period, in which the three participants' announcements can spoil at most 6.
  constexpr int kWindows = 8;
  bool clean_window = false;
  std::uint64_t published = 0;
  for (int window = 1; window <= kWindows && !clean_window; ++window) {
    const std::uint64_t tev_before = hubrt::testing::named_thread_allocations("tev");
    const std::uint64_t builtins_before = hubrt::testing::named_thread_allocations("dq.builtins");
    const std::uint64_t published_before = hub.nodes().front()->published();
    const std::uint64_t process_before = hubrt::testing::process_allocations();
    const std::uint64_t thread_before = hubrt::testing::thread_allocations();
    run(kMeasuredCycles);
    const std::uint64_t process = hubrt::testing::process_allocations() - process_before;
    const std::uint64_t cycle_thread = hubrt::testing::thread_allocations() - thread_before;
    const std::uint64_t tev = hubrt::testing::named_thread_allocations("tev") - tev_before;
    const std::uint64_t builtins = hubrt::testing::named_thread_allocations("dq.builtins") - builtins_before;
    const std::uint64_t elsewhere = process - cycle_thread - tev - builtins;
    published = hub.nodes().front()->published() - published_before;
    std::printf(
        "[alloc] %s, window %d: %d cycles at 1 kHz, %llu States published: %llu allocations in the whole "
        "process: %llu on the cycle thread, %llu on Cyclone's timed-event thread (tev), %llu on its "
        "discovery delivery thread (dq.builtins), %llu elsewhere\n",
        hubrt::testing::allocation_counting_method(), window, kMeasuredCycles,
        static_cast<unsigned long long>(published), static_cast<unsigned long long>(process),
        static_cast<unsigned long long>(cycle_thread), static_cast<unsigned long long>(tev),
        static_cast<unsigned long long>(builtins), static_cast<unsigned long long>(elsewhere));
    EXPECT_GE(published, static_cast<std::uint64_t>(kMeasuredCycles / 2));  // the hub did publish
    // The lease's announcements: at most one of each participant per window. (The cycle thread and
    // the others may still raise a high-water mark after a stall: the clean window settles them.)
    EXPECT_LE(tev, kOwnAnnouncementAllocations + kTimedEventOneOffs) << "window " << window;
    EXPECT_LE(builtins, kReceivedAnnouncementsAllocations) << "window " << window;
    clean_window = process == 0;
  }
  EXPECT_TRUE(clean_window) << "no window of " << kMeasuredCycles
                            << " cycles without a heap allocation in the whole process";
  // With the black box on: every State and command went through its hooks into its ring.
  ASSERT_NE((*assembled)->black_box, nullptr);
  EXPECT_GE((*assembled)->black_box->ring().recorded(), published);
}

}  // namespace
}  // namespace hubrt
