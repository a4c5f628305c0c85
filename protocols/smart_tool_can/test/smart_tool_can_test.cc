#include "hubrt/protocol/smart_tool_can.h"

#include <gtest/gtest.h>

namespace hubrt::protocol::smart_tool {
namespace {

constexpr std::uint8_t kNode = 5;

TEST(SmartToolCan, FrameIdsAreFunctionBasePlusNodeId) {
  EXPECT_EQ(frame_id(Function::kRunCommand, kNode), 0x085U);
  EXPECT_EQ(frame_id(Function::kProgramSelect, kNode), 0x105U);
  EXPECT_EQ(frame_id(Function::kStatus, kNode), 0x185U);
  EXPECT_EQ(frame_id(Function::kResult, kNode), 0x205U);
  EXPECT_EQ(frame_id(Function::kProgramAck, kNode), 0x285U);
  EXPECT_EQ(frame_id(Function::kHeartbeat, kNode), 0x705U);
  // The highest node id must not run into the next function's range.
  EXPECT_LT(frame_id(Function::kRunCommand, kMaxNodeId), frame_id(Function::kProgramSelect, 0));
}

TEST(SmartToolCan, ProgramSelectLayoutIsLittleEndianAsDocumented) {
  const Program p{7, 0x04D2, 0x0102, 0x0A0B};
  const hal::CanFrame f = encode(kNode, p);
  EXPECT_EQ(f.id, 0x105U);
  EXPECT_FALSE(f.extended);
  ASSERT_EQ(f.len, 8);
  const std::array<std::uint8_t, 8> expected{0x07, 0xD2, 0x04, 0x02, 0x01, 0x0B, 0x0A, 0x00};
  EXPECT_EQ(f.data, expected);
  EXPECT_EQ(decode_program_select(f, kNode), p);
}

TEST(SmartToolCan, ResultLayoutAsDocumented) {
  const RunResult r{3, 1000, 1800, false, nok_reason::kAngleLow, 42};
  const hal::CanFrame f = encode(kNode, r);
  EXPECT_EQ(f.id, 0x205U);
  const std::array<std::uint8_t, 8> expected{0x03, 0xE8, 0x03, 0x08, 0x07, 0x00, 0x02, 42};
  EXPECT_EQ(f.data, expected);
  EXPECT_EQ(decode_result(f, kNode), r);
}

TEST(SmartToolCan, EveryMessageRoundTrips) {
  const RunCommand start{Command::kStart, Direction::kReverse};
  EXPECT_EQ(decode_run_command(encode(kNode, start), kNode), start);
  const ProgramAck ack{Program{1, 2, 3, 4}, AckCode::kBusy};
  EXPECT_EQ(decode_program_ack(encode(kNode, ack), kNode), ack);
  const Status status{
      status_flag::kRunning | status_flag::kProgramSelected, alarm_bit::kOvertemperature, 523, 1777, 9, 200};
  EXPECT_EQ(decode_status(encode(kNode, status), kNode), status);
  const Heartbeat hb{255, ControllerState::kAlarm};
  EXPECT_EQ(decode_heartbeat(encode(kNode, hb), kNode), hb);
}

TEST(SmartToolCan, StopAndResetSendDirectionZero) {
  const hal::CanFrame f = encode(kNode, RunCommand{Command::kStop, Direction::kReverse});
  EXPECT_EQ(f.len, 2);
  EXPECT_EQ(f.data[0], 0x00);
  EXPECT_EQ(f.data[1], 0x00);
}

TEST(SmartToolCan, DecodersRejectOtherNodesFormatsAndLengths) {
  hal::CanFrame f = encode(kNode, Heartbeat{1, ControllerState::kIdle});
  EXPECT_FALSE(decode_heartbeat(f, kNode + 1).has_value());
  EXPECT_FALSE(decode_status(f, kNode).has_value());
  hal::CanFrame extended = f;
  extended.extended = true;
  EXPECT_FALSE(decode_heartbeat(extended, kNode).has_value());
  hal::CanFrame remote = f;
  remote.remote = true;
  EXPECT_FALSE(decode_heartbeat(remote, kNode).has_value());
  hal::CanFrame short_frame = f;
  short_frame.len = 1;
  EXPECT_FALSE(decode_heartbeat(short_frame, kNode).has_value());
}

TEST(SmartToolCan, DecodersRejectUndefinedValues) {
  hal::CanFrame cmd = encode(kNode, RunCommand{Command::kStart, Direction::kForward});
  cmd.data[0] = 3;
  EXPECT_FALSE(decode_run_command(cmd, kNode).has_value());
  cmd.data[0] = 1;
  cmd.data[1] = 2;
  EXPECT_FALSE(decode_run_command(cmd, kNode).has_value());

  hal::CanFrame hb = encode(kNode, Heartbeat{1, ControllerState::kIdle});
  hb.data[1] = 0;
  EXPECT_FALSE(decode_heartbeat(hb, kNode).has_value());

  // OK with NOK reasons, or NOK without any, is contradictory.
  hal::CanFrame ok_with_reason = encode(kNode, RunResult{1, 1, 1, true, 0, 1});
  ok_with_reason.data[6] = nok_reason::kAngleLow;
  EXPECT_FALSE(decode_result(ok_with_reason, kNode).has_value());
  hal::CanFrame nok_without_reason = encode(kNode, RunResult{1, 1, 1, false, nok_reason::kAlarm, 1});
  nok_without_reason.data[6] = 0;
  EXPECT_FALSE(decode_result(nok_without_reason, kNode).has_value());
}

TEST(SmartToolCan, ProgramValidity) {
  EXPECT_TRUE(valid_program(Program{1, 1, 0, 0}));
  EXPECT_FALSE(valid_program(Program{0, 100, 0, 10}));
  EXPECT_FALSE(valid_program(Program{1, 0, 0, 10}));
  EXPECT_FALSE(valid_program(Program{1, 100, 11, 10}));
}

TEST(SmartToolCan, FiltersSelectExactlyTheDirectionsFrames) {
  const auto hub = hub_filters(kNode);
  const auto controller = controller_filters(kNode);
  auto passes = [](const auto& filters, std::uint32_t id) {
    for (const hal::CanFilter& f : filters) {
      if (!f.extended && (id & f.mask) == (f.id & f.mask)) return true;
    }
    return false;
  };
  EXPECT_TRUE(passes(hub, 0x185));
  EXPECT_TRUE(passes(hub, 0x205));
  EXPECT_TRUE(passes(hub, 0x285));
  EXPECT_TRUE(passes(hub, 0x705));
  EXPECT_FALSE(passes(hub, 0x085));
  EXPECT_FALSE(passes(hub, 0x186));
  EXPECT_TRUE(passes(controller, 0x085));
  EXPECT_TRUE(passes(controller, 0x105));
  EXPECT_FALSE(passes(controller, 0x185));
  EXPECT_FALSE(passes(controller, 0x106));
}

TEST(SmartToolCan, ControllerLostAfterThreeMissedPeriodsPlusGrace) {
  EXPECT_EQ(kControllerLostAfter, std::chrono::milliseconds(350));
  EXPECT_DOUBLE_EQ(to_newton_metres(1234), 12.34);
  EXPECT_DOUBLE_EQ(to_degrees(1805), 180.5);
}

}  // namespace
}  // namespace hubrt::protocol::smart_tool
