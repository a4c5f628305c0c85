#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::protocol::smart_tool {
namespace {

constexpr std::uint32_t kExactStandardMask = 0x7FF;

hal::CanFrame make_frame(Function function, std::uint8_t node_id, std::uint8_t len) noexcept {
  hal::CanFrame frame;
  frame.id = frame_id(function, node_id);
  frame.len = len;
  return frame;
}

// Multi-byte fields are little-endian on the wire (docs/protocols/smart-tool-can.md, "Conventions").
void put_u16(hal::CanFrame& frame, std::size_t at, std::uint16_t value) noexcept {
  frame.data[at] = static_cast<std::uint8_t>(value & 0xFFU);
  frame.data[at + 1] = static_cast<std::uint8_t>(value >> 8U);
}

std::uint16_t get_u16(const hal::CanFrame& frame, std::size_t at) noexcept {
  return static_cast<std::uint16_t>(frame.data[at] | (frame.data[at + 1] << 8U));
}

bool matches(const hal::CanFrame& frame, Function function, std::uint8_t node_id, std::uint8_t len) noexcept {
  return !frame.extended && !frame.remote && frame.id == frame_id(function, node_id) && frame.len == len;
}

void put_program(hal::CanFrame& frame, const Program& p) noexcept {
  frame.data[0] = p.number;
  put_u16(frame, 1, p.torque_target_cnm);
  put_u16(frame, 3, p.angle_min_ddeg);
  put_u16(frame, 5, p.angle_max_ddeg);
}

Program get_program(const hal::CanFrame& frame) noexcept {
  return Program{frame.data[0], get_u16(frame, 1), get_u16(frame, 3), get_u16(frame, 5)};
}

hal::CanFilter exact(Function function, std::uint8_t node_id) noexcept {
  return hal::CanFilter{frame_id(function, node_id), kExactStandardMask, false};
}

}  // namespace

std::array<hal::CanFilter, 4> hub_filters(std::uint8_t node_id) noexcept {
  return {exact(Function::kStatus, node_id), exact(Function::kResult, node_id),
          exact(Function::kProgramAck, node_id), exact(Function::kHeartbeat, node_id)};
}

std::array<hal::CanFilter, 2> controller_filters(std::uint8_t node_id) noexcept {
  return {exact(Function::kRunCommand, node_id), exact(Function::kProgramSelect, node_id)};
}

hal::CanFrame encode(std::uint8_t node_id, const RunCommand& message) noexcept {
  hal::CanFrame frame = make_frame(Function::kRunCommand, node_id, 2);
  frame.data[0] = static_cast<std::uint8_t>(message.command);
  frame.data[1] = message.command == Command::kStart ? static_cast<std::uint8_t>(message.direction) : 0;
  return frame;
}

hal::CanFrame encode(std::uint8_t node_id, const Program& message) noexcept {
  hal::CanFrame frame = make_frame(Function::kProgramSelect, node_id, 8);
  put_program(frame, message);
  return frame;
}

hal::CanFrame encode(std::uint8_t node_id, const ProgramAck& message) noexcept {
  hal::CanFrame frame = make_frame(Function::kProgramAck, node_id, 8);
  put_program(frame, message.program);
  frame.data[7] = static_cast<std::uint8_t>(message.code);
  return frame;
}

hal::CanFrame encode(std::uint8_t node_id, const Status& message) noexcept {
  hal::CanFrame frame = make_frame(Function::kStatus, node_id, 8);
  frame.data[0] = message.flags;
  frame.data[1] = message.alarms;
  put_u16(frame, 2, message.torque_cnm);
  put_u16(frame, 4, message.angle_ddeg);
  frame.data[6] = message.program;
  frame.data[7] = message.run_counter;
  return frame;
}

hal::CanFrame encode(std::uint8_t node_id, const RunResult& message) noexcept {
  hal::CanFrame frame = make_frame(Function::kResult, node_id, 8);
  frame.data[0] = message.program;
  put_u16(frame, 1, message.torque_cnm);
  put_u16(frame, 3, message.angle_ddeg);
  frame.data[5] = message.ok ? 0x01 : 0x00;
  frame.data[6] = message.nok_reasons;
  frame.data[7] = message.run_counter;
  return frame;
}

hal::CanFrame encode(std::uint8_t node_id, const Heartbeat& message) noexcept {
  hal::CanFrame frame = make_frame(Function::kHeartbeat, node_id, 2);
  frame.data[0] = message.counter;
  frame.data[1] = static_cast<std::uint8_t>(message.state);
  return frame;
}

std::optional<RunCommand> decode_run_command(const hal::CanFrame& frame, std::uint8_t node_id) noexcept {
  if (!matches(frame, Function::kRunCommand, node_id, 2)) return std::nullopt;
  if (frame.data[0] > static_cast<std::uint8_t>(Command::kResetAlarm)) return std::nullopt;
  if (frame.data[1] > static_cast<std::uint8_t>(Direction::kReverse)) return std::nullopt;
  return RunCommand{static_cast<Command>(frame.data[0]), static_cast<Direction>(frame.data[1])};
}

std::optional<Program> decode_program_select(const hal::CanFrame& frame, std::uint8_t node_id) noexcept {
  if (!matches(frame, Function::kProgramSelect, node_id, 8)) return std::nullopt;
  return get_program(frame);
}

std::optional<ProgramAck> decode_program_ack(const hal::CanFrame& frame, std::uint8_t node_id) noexcept {
  if (!matches(frame, Function::kProgramAck, node_id, 8)) return std::nullopt;
  if (frame.data[7] > static_cast<std::uint8_t>(AckCode::kBusy)) return std::nullopt;
  return ProgramAck{get_program(frame), static_cast<AckCode>(frame.data[7])};
}

std::optional<Status> decode_status(const hal::CanFrame& frame, std::uint8_t node_id) noexcept {
  if (!matches(frame, Function::kStatus, node_id, 8)) return std::nullopt;
  return Status{frame.data[0],     frame.data[1], get_u16(frame, 2),
                get_u16(frame, 4), frame.data[6], frame.data[7]};
}

std::optional<RunResult> decode_result(const hal::CanFrame& frame, std::uint8_t node_id) noexcept {
  if (!matches(frame, Function::kResult, node_id, 8)) return std::nullopt;
  if (frame.data[5] > 0x01) return std::nullopt;
  const bool ok = frame.data[5] == 0x01;
  // OK and NOK reasons exclude each other; a frame claiming both is not ours to interpret.
  if (ok == (frame.data[6] != 0)) return std::nullopt;
  return RunResult{frame.data[0], get_u16(frame, 1), get_u16(frame, 3), ok, frame.data[6], frame.data[7]};
}

std::optional<Heartbeat> decode_heartbeat(const hal::CanFrame& frame, std::uint8_t node_id) noexcept {
  if (!matches(frame, Function::kHeartbeat, node_id, 2)) return std::nullopt;
  const std::uint8_t state = frame.data[1];
  if (state < static_cast<std::uint8_t>(ControllerState::kIdle) ||
      state > static_cast<std::uint8_t>(ControllerState::kAlarm)) {
    return std::nullopt;
  }
  return Heartbeat{frame.data[0], static_cast<ControllerState>(state)};
}

}  // namespace hubrt::protocol::smart_tool
