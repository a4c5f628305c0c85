// A new subscriber of a State gets one as soon as discovery matches it, not at the next heartbeat
// (issue 16, point 2): the hub publishes a node's State at once when a new State reader matches.
// Before, a reader that appeared just after a heartbeat waited a whole period for its first
// State: at the Dock ECU's 10 Hz, 100 ms; and a subscriber that waited for a hub to start lost the
// States written before discovery matched it (bench/programs/startup.cc measures that case).
#include <algorithm>
#include <chrono>
#include <iostream>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

constexpr char kStateTopic[] = "/dock_ecu/dock/state";

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// Takes the next State from `reader` within `timeout`; the time it was taken, or nullopt.
std::optional<Clock::time_point> take_one(dds::Reader<DockState>& reader, dds::Sample<DockState>& state,
                                          Duration timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    const Result<bool> taken = reader.take_next(state);
    if (taken.is_ok() && taken.value()) return Clock::now();
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  return std::nullopt;
}

TEST(HubdFirstState, ANewSubscriberGetsAStateLongBeforeTheNextHeartbeatAt10Hz) {
  test_support::HubUnderTest hub;
  ASSERT_NO_FATAL_FAILURE(hub.open("test-subscribers"));
  auto topic = dds::Topic<DockState>::create(hub.participant(), kStateTopic);
  ASSERT_TRUE(topic) << topic.error().message;
  auto watcher = dds::Reader<DockState>::create(hub.participant(), *topic);
  ASSERT_TRUE(watcher) << watcher.error().message;
  // The shipped Dock ECU rate: 10 Hz, a 100 ms period.
  constexpr double kPeriodMs = 100;
  ASSERT_NO_FATAL_FAILURE(hub.start({.extra_args = {"--rate", "10"}}));

  // Three rounds: each time a heartbeat has just arrived (fresh: stamped less than 10 ms ago, so
  // the next one is about a period away), a new reader subscribes and waits for its first State.
  std::vector<double> waits_ms;
  dds::Sample<DockState> state;
  for (int attempt = 0; attempt < 50 && waits_ms.size() < 3; ++attempt) {
    ASSERT_TRUE(take_one(*watcher, state, std::chrono::seconds(10))) << hub.output();
    const auto& stamp = state.get().header.stamp;
    const double age_s = wall_seconds() - (stamp.sec + stamp.nanosec * 1e-9);
    if (age_s > 0.010) continue;  // delivered late: the next heartbeat may be near
    const auto subscribed_at = Clock::now();
    auto late = dds::Reader<DockState>::create(hub.participant(), *topic);
    ASSERT_TRUE(late) << late.error().message;
    dds::Sample<DockState> first;
    const auto got = take_one(*late, first, std::chrono::seconds(5));
    ASSERT_TRUE(got) << "the new reader got no State at all: " << hub.output();
    waits_ms.push_back(std::chrono::duration<double, std::milli>(*got - subscribed_at).count());
    while (watcher->take_next(state).value_or(false)) {
    }
  }
  ASSERT_EQ(waits_ms.size(), 3u) << "no fresh heartbeat to start from: " << hub.output();
  std::cout << "new reader -> first State: " << waits_ms[0] << ", " << waits_ms[1] << ", " << waits_ms[2]
            << " ms\n";
  // Without the publish on match the first State is the next heartbeat: about a period (100 ms)
  // after a fresh one, in every round. With it, the State follows the match (discovery of one new
  // endpoint on loopback: a few ms). Judged on the best of the three rounds against half a period,
  // so that a loaded 2-core machine running sanitizer builds may stall one or two of them.
  const double best = *std::min_element(waits_ms.begin(), waits_ms.end());
  EXPECT_LT(best, kPeriodMs / 2)
      << "a new reader waited for the heartbeat instead of getting a State at once";
}

}  // namespace
}  // namespace hubrt::integration
