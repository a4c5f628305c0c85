// The simulator in real time, as the running hub sees it: a blocking receive driven by a
// SystemClock, and a tool-side thread injecting faults while the hub's thread uses the bus.
// Bounds are generous (shared 2-core machine); each says what it guards against.
#include <atomic>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/hal/fake/smart_tool_simulator.h"

namespace hubrt::hal::fake {
namespace {

namespace st = protocol::smart_tool;
using std::chrono::milliseconds;
using std::chrono::seconds;
using Steady = std::chrono::steady_clock;

constexpr std::uint8_t kNode = 1;

std::unique_ptr<VirtualCanNode> open_hub(VirtualCanNetwork& net) {
  CanConfig c;
  c.bus = "hub";
  c.interface = "vcan0";
  const auto filters = st::hub_filters(kNode);
  c.filters.assign(filters.begin(), filters.end());
  return std::move(*net.open(c));
}

TEST(SmartToolSimulatorThreaded, BlockingReceiveGetsHeartbeatsInRealTime) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  SmartToolSimulatorConfig config;
  config.heartbeat_period = milliseconds(20);
  auto sim = std::move(*SmartToolSimulator::create(net, config));
  auto hub = open_hub(net);

  const auto start = Steady::now();
  std::vector<std::uint8_t> counters;
  while (counters.size() < 5) {
    const Result<CanFrame> f = hub->receive(seconds(1));
    ASSERT_TRUE(f.is_ok()) << "no frame within 1 s although one is due every 20 ms";
    if (const auto hb = st::decode_heartbeat(f.value(), kNode)) counters.push_back(hb->counter);
  }
  for (std::size_t i = 0; i < counters.size(); ++i) EXPECT_EQ(counters[i], static_cast<std::uint8_t>(i));
  // 5 heartbeats take 80 ms; 2 s only catches a receiver that sleeps through due devices.
  EXPECT_LT(Steady::now() - start, seconds(2));
}

TEST(SmartToolSimulatorThreaded, ToolSideAlarmEndsARunTheHubIsWaitingOn) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  auto sim = std::move(*SmartToolSimulator::create(net, SmartToolSimulatorConfig{}));
  auto hub = open_hub(net);
  // 90 Nm at 20 Nm/s: 4.5 s, so that the alarm, not the torque, ends the run.
  const st::Program program{1, 9000, 0, 65000};
  ASSERT_TRUE(hub->send(st::encode(kNode, program), milliseconds(10)).is_ok());
  ASSERT_TRUE(hub->send(st::encode(kNode, st::RunCommand{st::Command::kStart, st::Direction::kForward}),
                        milliseconds(10))
                  .is_ok());

  std::thread tool_side([&] {
    const auto deadline = Steady::now() + seconds(5);
    while (!sim->snapshot().running && Steady::now() < deadline) std::this_thread::sleep_for(milliseconds(1));
    sim->raise_alarm(st::alarm_bit::kOvertemperature);
  });

  std::optional<st::RunResult> result;
  const auto deadline = Steady::now() + seconds(4);
  while (!result && Steady::now() < deadline) {
    const Result<CanFrame> f = hub->receive(milliseconds(50));
    if (f.is_ok()) result = st::decode_result(f.value(), kNode);
  }
  tool_side.join();
  ASSERT_TRUE(result.has_value()) << "the alarm's NOK result never reached the hub";
  EXPECT_FALSE(result->ok);
  EXPECT_EQ(result->nok_reasons, st::nok_reason::kAlarm | st::nok_reason::kTorqueLow);
}

TEST(SmartToolSimulatorThreaded, FaultInjectionRacesTheHubCycleSafely) {
  SystemClock clock;
  VirtualCanNetwork net(clock);
  SmartToolSimulatorConfig config;
  config.heartbeat_period = milliseconds(5);
  auto sim = std::move(*SmartToolSimulator::create(net, config));
  auto hub = open_hub(net);

  std::atomic<bool> stop{false};
  std::thread tool_side([&] {
    for (int i = 0; !stop.load(); ++i) {
      sim->set_joint_slip(i % 2 == 0);
      sim->set_bus_off(i % 7 == 3);
      if (i % 5 == 0) sim->raise_alarm(st::alarm_bit::kTransducerFault);
      static_cast<void>(sim->snapshot());
      std::this_thread::yield();
    }
    sim->set_bus_off(false);
  });
  int heartbeats = 0;
  const auto until = Steady::now() + milliseconds(300);
  while (Steady::now() < until) {
    hub->send(st::encode(kNode, st::Program{1, 500, 0, 65000}), Duration::zero()).ignore();
    hub->send(st::encode(kNode, st::RunCommand{st::Command::kResetAlarm, st::Direction::kForward}),
              Duration::zero())
        .ignore();
    hub->send(st::encode(kNode, st::RunCommand{st::Command::kStart, st::Direction::kForward}),
              Duration::zero())
        .ignore();
    for (Result<CanFrame> f = hub->receive(milliseconds(2)); f.is_ok(); f = hub->receive(Duration::zero())) {
      if (st::decode_heartbeat(f.value(), kNode)) ++heartbeats;
    }
  }
  stop = true;
  tool_side.join();
  // 300 ms at a 5 ms period is 60 heartbeats; some fall in bus-off windows. One proves the hub
  // kept receiving while the tool side hammered the simulator (TSan checks the rest).
  EXPECT_GT(heartbeats, 0);
}

}  // namespace
}  // namespace hubrt::hal::fake
