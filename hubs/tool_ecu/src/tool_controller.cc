#include "tool_controller.h"

#include <utility>

namespace hubrt::tool_ecu {

namespace st = protocol::smart_tool;

namespace {
// Sending never waits: a full transmit queue is a fault to report, not something to sit out.
constexpr Duration kNoWait{0};

std::string_view bus_state_name(hal::CanBusState state) noexcept {
  switch (state) {
    case hal::CanBusState::kBusOff:
      return "bus-off";
    case hal::CanBusState::kDown:
      return "interface down";
    case hal::CanBusState::kErrorPassive:
      return "error passive";
    case hal::CanBusState::kErrorWarning:
      return "error warning";
    case hal::CanBusState::kErrorActive:
      break;
  }
  return "error active";
}
}  // namespace

hal::CanConfig ToolController::bus_config(hal::CanConfig board_bus, std::uint8_t node_id) {
  const auto filters = st::hub_filters(node_id);
  board_bus.filters.assign(filters.begin(), filters.end());
  return board_bus;
}

void ToolController::poll(Time now) noexcept {
  const bool was_open = bus_.is_open();
  hal::CanBus* bus = bus_.device(now);
  if (bus == nullptr) return;
  if (!was_open) {  // (re)opened just now: nothing wrong with it yet
    bus_fault_ = false;
    bus_state_off_ = false;
    bus_problem_.clear();
  }
  bool failed = false;
  for (int i = 0; i < kMaxFramesPerPoll; ++i) {
    const Result<hal::CanFrame> frame = bus->receive(kNoWait);
    if (frame.is_ok()) {
      handle(frame.value(), now);
      continue;
    }
    if (frame.status().code() != ErrorCode::kTimeout) {
      note_failure("receive failed", frame.status().code());
      failed = true;
      // Lets the supervisor drop a bus its contract says is gone (a CAN bus never is: it
      // recovers from down and bus-off itself; see supervised_device.h).
      bus_.observe(frame.status().code(), now);
      if (!bus_.is_open()) return;
    }
    break;
  }
  const hal::CanBusStatus bus_status = bus->status();
  bus_state_off_ =
      bus_status.state == hal::CanBusState::kBusOff || bus_status.state == hal::CanBusState::kDown;
  if (bus_state_off_) {
    bus_fault_ = true;
    bus_problem_.format("CAN bus {} ({}): {}", can_config().bus, can_config().interface,
                        bus_state_name(bus_status.state));
  } else if (!failed) {
    bus_fault_ = false;
    bus_problem_.clear();
  }
}

void ToolController::handle(const hal::CanFrame& frame, Time now) noexcept {
  if (auto beat = st::decode_heartbeat(frame, node_id_)) {
    note_heartbeat(*beat, now);
  } else if (auto status = st::decode_status(frame, node_id_)) {
    status_ = *status;
    ++status_count_;
    last_status_ = now;
  } else if (auto result = st::decode_result(frame, node_id_)) {
    result_ = *result;
  } else if (auto ack = st::decode_program_ack(frame, node_id_)) {
    ack_ = *ack;
  }
  // Anything else (other ids, wrong DLC, undefined values) is ignored, as the protocol says.
}

void ToolController::note_heartbeat(const st::Heartbeat& beat, Time now) noexcept {
  if (heartbeats_ > 0) {
    const auto expected = static_cast<std::uint8_t>(heartbeat_.counter + 1);
    if (beat.counter == 0 && heartbeat_.counter != 255) {
      ++reboots_;  // the controller starts counting at 0 after power-up
    } else if (beat.counter != expected) {
      missed_heartbeats_ += static_cast<std::uint8_t>(beat.counter - expected);
    }
  }
  heartbeat_ = beat;
  last_heartbeat_ = now;
  ++heartbeats_;
}

Status ToolController::send(const hal::CanFrame& frame) noexcept {
  hal::CanBus* bus = bus_.device_if_open();
  if (bus == nullptr) return Status(ErrorCode::kUnavailable);
  const Status sent = bus->send(frame, kNoWait);
  if (!sent.is_ok()) note_failure("send failed", sent.code());
  return sent;
}

void ToolController::note_failure(std::string_view what, ErrorCode code) noexcept {
  if (bus_fault_ && bus_state_off_) return;  // the bus state says it better than the failed call
  bus_fault_ = true;
  bus_problem_.format("CAN bus {} ({}): {}: {}", can_config().bus, can_config().interface, what,
                      to_string(code));
}

Status ToolController::start(st::Direction direction) noexcept {
  return send(st::encode(node_id_, st::RunCommand{st::Command::kStart, direction}));
}

Status ToolController::stop() noexcept {
  return send(st::encode(node_id_, st::RunCommand{st::Command::kStop, st::Direction::kForward}));
}

Status ToolController::reset_alarm() noexcept {
  return send(st::encode(node_id_, st::RunCommand{st::Command::kResetAlarm, st::Direction::kForward}));
}

Status ToolController::select(const st::Program& program) noexcept {
  return send(st::encode(node_id_, program));
}

}  // namespace hubrt::tool_ecu
