// The smart tool controller simulator against docs/protocols/smart-tool-can.md, driven by a
// ManualClock: the hub side is a plain node on the virtual bus that polls with timeout 0.
#include "hubrt/hal/fake/smart_tool_simulator.h"

#include <vector>

#include <gtest/gtest.h>

namespace hubrt::hal::fake {
namespace {

namespace st = protocol::smart_tool;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::uint8_t kNode = 3;
// 20 Nm/s, 360 °/s (defaults): a 10 Nm target is reached after 500 ms at 180.0°.
const st::Program kProgram{12, 1000, 1500, 2000};

class SmartToolSimulatorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    SmartToolSimulatorConfig config;
    config.interface = "tool_can";
    config.node_id = kNode;
    auto created = SmartToolSimulator::create(net, config);
    ASSERT_TRUE(created.is_ok()) << created.error().message;
    sim = std::move(*created);
    CanConfig hub_config;
    hub_config.bus = "hub";
    hub_config.interface = "tool_can";
    const auto filters = st::hub_filters(kNode);
    hub_config.filters.assign(filters.begin(), filters.end());
    hub = std::move(*net.open(hub_config));
    t0 = clock.now().mono;
  }

  // Everything the controller sent up to the clock's now.
  std::vector<CanFrame> drain() {
    std::vector<CanFrame> frames;
    for (Result<CanFrame> f = hub->receive(Duration::zero()); f.is_ok(); f = hub->receive(Duration::zero())) {
      frames.push_back(f.value());
    }
    return frames;
  }
  template <class Decoder>
  static auto all_of(const std::vector<CanFrame>& frames, Decoder decode) {
    std::vector<typename decltype(decode(CanFrame{}, kNode))::value_type> out;
    for (const CanFrame& f : frames) {
      if (auto m = decode(f, kNode)) out.push_back(*m);
    }
    return out;
  }
  static std::vector<st::Heartbeat> heartbeats(const std::vector<CanFrame>& f) {
    return all_of(f, st::decode_heartbeat);
  }
  static std::vector<st::Status> statuses(const std::vector<CanFrame>& f) {
    return all_of(f, st::decode_status);
  }
  static std::vector<st::RunResult> results(const std::vector<CanFrame>& f) {
    return all_of(f, st::decode_result);
  }
  static std::vector<st::ProgramAck> acks(const std::vector<CanFrame>& f) {
    return all_of(f, st::decode_program_ack);
  }

  void send(const st::RunCommand& command) {
    ASSERT_TRUE(hub->send(st::encode(kNode, command), Duration::zero()).is_ok());
  }
  void select(const st::Program& program) {
    ASSERT_TRUE(hub->send(st::encode(kNode, program), Duration::zero()).is_ok());
  }
  void start_forward() { send(st::RunCommand{st::Command::kStart, st::Direction::kForward}); }

  ManualClock clock;
  VirtualCanNetwork net{clock};
  std::unique_ptr<SmartToolSimulator> sim;
  std::unique_ptr<VirtualCanNode> hub;
  Time t0;
};

TEST_F(SmartToolSimulatorTest, HeartbeatEveryPeriodWithConsecutiveCounter) {
  auto first = heartbeats(drain());
  ASSERT_EQ(first.size(), 1U) << "boot heartbeat at power-on";
  EXPECT_EQ(first[0].counter, 0);
  EXPECT_EQ(first[0].state, st::ControllerState::kIdle);

  clock.advance(milliseconds(99));
  EXPECT_TRUE(heartbeats(drain()).empty()) << "not before the period";
  clock.advance(milliseconds(1));
  ASSERT_EQ(heartbeats(drain()).size(), 1U);

  clock.advance(seconds(1));
  const auto burst = heartbeats(drain());
  ASSERT_EQ(burst.size(), 10U);
  for (std::size_t i = 0; i < burst.size(); ++i) EXPECT_EQ(burst[i].counter, i + 2);
}

TEST_F(SmartToolSimulatorTest, StatusFollowsEveryHeartbeat) {
  clock.advance(milliseconds(300));
  const auto frames = drain();
  EXPECT_EQ(heartbeats(frames).size(), 4U);
  EXPECT_EQ(statuses(frames).size(), 4U);
  EXPECT_EQ(statuses(frames).back().flags, 0) << "idle, no program";
}

TEST_F(SmartToolSimulatorTest, ProgramSelectIsAcknowledgedWithAnEcho) {
  drain();
  select(kProgram);
  const auto frames = drain();
  const auto ack = acks(frames);
  ASSERT_EQ(ack.size(), 1U);
  EXPECT_EQ(ack[0].program, kProgram);
  EXPECT_EQ(ack[0].code, st::AckCode::kAccepted);
  ASSERT_FALSE(statuses(frames).empty()) << "status goes out at once when the program changes";
  EXPECT_TRUE(statuses(frames).back().flags & st::status_flag::kProgramSelected);
  EXPECT_EQ(statuses(frames).back().program, kProgram.number);

  select(st::Program{13, 1000, 2000, 1000});
  const auto rejected = acks(drain());
  ASSERT_EQ(rejected.size(), 1U);
  EXPECT_EQ(rejected[0].code, st::AckCode::kInvalid);
  EXPECT_EQ(sim->snapshot().program, kProgram) << "an invalid program leaves the selected one";
}

TEST_F(SmartToolSimulatorTest, ForwardRunRampsTorqueAndReportsAnOkResult) {
  select(kProgram);
  drain();
  start_forward();
  const auto started = statuses(drain());
  ASSERT_FALSE(started.empty());
  EXPECT_TRUE(started.back().flags & st::status_flag::kRunning);
  EXPECT_EQ(started.back().run_counter, 1);

  clock.advance(milliseconds(200));
  const auto live = statuses(drain());
  ASSERT_FALSE(live.empty());
  EXPECT_EQ(live.back().torque_cnm, 400) << "20 Nm/s for 200 ms";
  EXPECT_EQ(live.back().angle_ddeg, 720) << "360 °/s for 200 ms";

  clock.advance(milliseconds(299));
  EXPECT_TRUE(results(drain()).empty()) << "1 ms before the torque is reached";
  clock.advance(milliseconds(1));
  const auto frames = drain();
  const auto result = results(frames);
  ASSERT_EQ(result.size(), 1U);
  EXPECT_TRUE(result[0].ok);
  EXPECT_EQ(result[0].nok_reasons, 0);
  EXPECT_EQ(result[0].torque_cnm, 1000);
  EXPECT_EQ(result[0].angle_ddeg, 1800);
  EXPECT_EQ(result[0].program, kProgram.number);
  EXPECT_EQ(result[0].run_counter, 1);
  const auto after = statuses(frames);
  ASSERT_FALSE(after.empty());
  EXPECT_FALSE(after.back().flags & st::status_flag::kRunning);
  EXPECT_TRUE(after.back().flags & st::status_flag::kTorqueReached);
  EXPECT_EQ(after.back().torque_cnm, 1000);
}

TEST_F(SmartToolSimulatorTest, TorqueReachedBelowTheAngleWindowIsNok) {
  select(st::Program{1, 1000, 2000, 3000});
  start_forward();
  clock.advance(milliseconds(500));
  const auto result = results(drain());
  ASSERT_EQ(result.size(), 1U);
  EXPECT_FALSE(result[0].ok);
  EXPECT_EQ(result[0].nok_reasons, st::nok_reason::kAngleLow);
  EXPECT_EQ(result[0].torque_cnm, 1000);
}

TEST_F(SmartToolSimulatorTest, StopBeforeTheTorqueIsNokAndRepeatedStopIsHarmless) {
  select(kProgram);
  start_forward();
  clock.advance(milliseconds(200));
  drain();
  send(st::RunCommand{st::Command::kStop, st::Direction::kForward});
  send(st::RunCommand{st::Command::kStop, st::Direction::kForward});
  const auto result = results(drain());
  ASSERT_EQ(result.size(), 1U) << "one run, one result";
  EXPECT_FALSE(result[0].ok);
  EXPECT_EQ(result[0].nok_reasons, st::nok_reason::kStoppedByCommand | st::nok_reason::kTorqueLow);
  EXPECT_EQ(result[0].torque_cnm, 400);
  EXPECT_FALSE(sim->snapshot().running);
}

TEST_F(SmartToolSimulatorTest, StartIsIgnoredWithoutProgramAndWhileRunning) {
  start_forward();
  clock.advance(milliseconds(100));
  EXPECT_FALSE(sim->snapshot().running);
  EXPECT_EQ(sim->snapshot().run_counter, 0);

  select(kProgram);
  start_forward();
  start_forward();  // repeated: still one run
  EXPECT_EQ(sim->snapshot().run_counter, 1);
  select(st::Program{2, 500, 0, 100});
  drain();
  clock.advance(milliseconds(10));
  select(st::Program{2, 500, 0, 100});
  const auto busy = acks(drain());
  ASSERT_EQ(busy.size(), 1U);
  EXPECT_EQ(busy[0].code, st::AckCode::kBusy);
  EXPECT_EQ(sim->snapshot().program, kProgram);
}

TEST_F(SmartToolSimulatorTest, JointSlipEndsTheRunNokPastTheAngleWindow) {
  sim->set_joint_slip(true);
  select(st::Program{1, 1000, 0, 3000});
  start_forward();
  clock.advance(seconds(1));
  const auto result = results(drain());
  ASSERT_EQ(result.size(), 1U);
  EXPECT_FALSE(result[0].ok);
  EXPECT_EQ(result[0].nok_reasons, st::nok_reason::kAngleHigh | st::nok_reason::kTorqueLow);
  EXPECT_EQ(result[0].torque_cnm, 300) << "stalled at 30 % of the target";
  EXPECT_EQ(result[0].angle_ddeg, 3001);
}

TEST_F(SmartToolSimulatorTest, AlarmEndsTheRunBlocksStartsAndClearsOnReset) {
  select(kProgram);
  start_forward();
  clock.advance(milliseconds(100));
  drain();
  sim->raise_alarm(st::alarm_bit::kOvercurrent);
  const auto frames = drain();
  const auto result = results(frames);
  ASSERT_EQ(result.size(), 1U);
  EXPECT_EQ(result[0].nok_reasons, st::nok_reason::kAlarm | st::nok_reason::kTorqueLow);
  ASSERT_FALSE(statuses(frames).empty());
  EXPECT_EQ(statuses(frames).back().alarms, st::alarm_bit::kOvercurrent);
  EXPECT_TRUE(statuses(frames).back().flags & st::status_flag::kAlarm);

  clock.advance(milliseconds(100));
  const auto hb = heartbeats(drain());
  ASSERT_EQ(hb.size(), 1U);
  EXPECT_EQ(hb[0].state, st::ControllerState::kAlarm);

  start_forward();
  EXPECT_FALSE(sim->snapshot().running) << "no start while an alarm is latched";
  send(st::RunCommand{st::Command::kResetAlarm, st::Direction::kForward});
  EXPECT_EQ(sim->snapshot().alarms, 0);
  start_forward();
  EXPECT_TRUE(sim->snapshot().running);
}

TEST_F(SmartToolSimulatorTest, ReverseRunTurnsUntilStopAndSendsNoResult) {
  send(st::RunCommand{st::Command::kStart, st::Direction::kReverse});
  const auto started = statuses(drain());
  ASSERT_FALSE(started.empty());
  EXPECT_EQ(started.back().flags & (st::status_flag::kRunning | st::status_flag::kReverse),
            st::status_flag::kRunning | st::status_flag::kReverse)
      << "reverse needs no program";
  clock.advance(seconds(1));
  drain();
  send(st::RunCommand{st::Command::kStop, st::Direction::kForward});
  const auto frames = drain();
  EXPECT_TRUE(results(frames).empty());
  ASSERT_FALSE(statuses(frames).empty());
  EXPECT_EQ(statuses(frames).back().flags & st::status_flag::kRunning, 0);
  EXPECT_EQ(statuses(frames).back().angle_ddeg, 3600);
}

TEST_F(SmartToolSimulatorTest, PowerOffSilencesTheControllerUntilItBootsAgain) {
  select(kProgram);
  clock.advance(milliseconds(250));
  drain();
  const Time last_heartbeat = t0 + milliseconds(200);
  sim->power_off();
  clock.advance(seconds(1));
  EXPECT_TRUE(drain().empty()) << "a lost controller sends nothing";
  EXPECT_GT(clock.now().mono - last_heartbeat, st::kControllerLostAfter);

  sim->power_on();
  const auto frames = drain();
  const auto hb = heartbeats(frames);
  ASSERT_EQ(hb.size(), 1U);
  EXPECT_EQ(hb[0].counter, 0) << "a reboot restarts the counter";
  EXPECT_FALSE(sim->snapshot().program.has_value()) << "and forgets the program";
}

TEST_F(SmartToolSimulatorTest, ControllerBusOffAbortsTheRunAndReportsItAfterRecovery) {
  select(kProgram);
  start_forward();
  clock.advance(milliseconds(150));
  drain();
  sim->set_bus_off(true);
  clock.advance(milliseconds(400));
  EXPECT_TRUE(drain().empty());
  EXPECT_FALSE(sim->snapshot().running) << "the motor stops while the hub cannot reach the controller";

  sim->set_bus_off(false);
  clock.advance(milliseconds(50));
  const auto frames = drain();
  ASSERT_FALSE(frames.empty());
  const auto result = st::decode_result(frames.front(), kNode);
  ASSERT_TRUE(result.has_value()) << "the aborted run's result comes first";
  EXPECT_EQ(result->nok_reasons, st::nok_reason::kLinkLost | st::nok_reason::kTorqueLow);
  EXPECT_EQ(result->torque_cnm, 300);
  const auto hb = heartbeats(frames);
  ASSERT_EQ(hb.size(), 1U);
  EXPECT_EQ(hb[0].counter, 6) << "heartbeats 2..5 were lost while bus-off: the gap shows it";
}

TEST_F(SmartToolSimulatorTest, WholeBusOffIsSeenByTheHubAndAbortsTheRun) {
  select(kProgram);
  start_forward();
  clock.advance(milliseconds(100));
  drain();
  net.set_bus_state("tool_can", CanBusState::kBusOff);
  EXPECT_EQ(hub->status().state, CanBusState::kBusOff);
  EXPECT_EQ(hub->send(st::encode(kNode, st::RunCommand{}), Duration::zero()).code(), ErrorCode::kUnavailable);
  EXPECT_FALSE(sim->snapshot().running);
  net.set_bus_state("tool_can", CanBusState::kErrorActive);
  const auto result = results(drain());
  ASSERT_EQ(result.size(), 1U);
  EXPECT_EQ(result[0].nok_reasons, st::nok_reason::kLinkLost | st::nok_reason::kTorqueLow);
}

TEST(SmartToolSimulatorConfigTest, RejectsInvalidConfiguration) {
  ManualClock clock;
  VirtualCanNetwork net(clock);
  SmartToolSimulatorConfig bad_node;
  bad_node.node_id = 0;
  EXPECT_FALSE(SmartToolSimulator::create(net, bad_node).is_ok());
  SmartToolSimulatorConfig bad_rate;
  bad_rate.physics.torque_rate_nm_per_s = 0.0;
  const auto err = SmartToolSimulator::create(net, bad_rate);
  ASSERT_FALSE(err.is_ok());
  EXPECT_EQ(err.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(err.error().message.find("vcan0"), std::string::npos) << err.error().message;
}

}  // namespace
}  // namespace hubrt::hal::fake
