// The hub's side of the smart tool controller's CAN link (docs/protocols/smart-tool-can.md):
// the bus (a supervised device, opened again until it works), what the controller last said (heartbeat,
// status, result, program acknowledgement) and the frames the hub sends. No decisions: SmartToolLogic
// decides; this keeps the protocol bookkeeping out of it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/protocol/smart_tool_can.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::tool_ecu {

// Not thread-safe: owned by the smart tool node on the cycle thread. Polling and sending never
// block (receive with timeout 0, send with timeout 0) and never allocate; reopening the bus does.
class ToolController {
 public:
  // Frames taken per poll at most, so a flooded bus cannot stall the cycle.
  static constexpr int kMaxFramesPerPoll = 64;

  // The board's bus with its filters replaced by the four ids of controller `node_id`: what the
  // hub type opens for this controller.
  static hal::CanConfig bus_config(hal::CanConfig board_bus, std::uint8_t node_id);

  // `bus` as the hub type opened it (bus_config()); one not open yet is reported by bus_problem()
  // and retried by poll() with the supervised device's back-off.
  ToolController(hal::SupervisedCanBus bus, std::uint8_t node_id) noexcept
      : bus_(std::move(bus)), node_id_(node_id) {}

  // Opens the bus if it is not open and a retry is due (that allocates), takes every waiting frame
  // and samples the bus state.
  void poll(Time now) noexcept;

  // Frames to the controller. Errors: kUnavailable (bus not open, bus-off, down), kTimeout (transmit
  // queue full), kIo. A failure also counts as a bus fault until the next successful poll or send.
  Status start(protocol::smart_tool::Direction direction) noexcept;
  Status stop() noexcept;
  Status reset_alarm() noexcept;
  Status select(const protocol::smart_tool::Program& program) noexcept;

  // --- heartbeat ---
  [[nodiscard]] bool ever_heard() const noexcept { return heartbeats_ > 0; }
  // A heartbeat came within protocol::smart_tool::kControllerLostAfter.
  [[nodiscard]] bool online(Time now) const noexcept {
    return ever_heard() && now - last_heartbeat_ <= protocol::smart_tool::kControllerLostAfter;
  }
  [[nodiscard]] Duration silent_for(Time now) const noexcept { return now - last_heartbeat_; }
  [[nodiscard]] const protocol::smart_tool::Heartbeat& heartbeat() const noexcept { return heartbeat_; }
  // Heartbeats the counter says were lost (jumps by more than one), and reboots seen (counter
  // back at 0 other than by wrapping), since start.
  [[nodiscard]] std::uint32_t missed_heartbeats() const noexcept { return missed_heartbeats_; }
  [[nodiscard]] std::uint32_t reboots() const noexcept { return reboots_; }

  // --- status: the latest; status_count() grows by one per status frame received ---
  [[nodiscard]] bool has_status() const noexcept { return status_count_ > 0; }
  [[nodiscard]] const protocol::smart_tool::Status& status() const noexcept { return status_; }
  [[nodiscard]] std::uint64_t status_count() const noexcept { return status_count_; }
  // When the latest status was received (the poll's time); meaningless before the first.
  [[nodiscard]] Time status_received_at() const noexcept { return last_status_; }
  // A status arrived within protocol::smart_tool::kControllerLostAfter: the controller sends one
  // every 100 ms, so the heartbeat's limit applies to it too. Older values are not current.
  [[nodiscard]] bool status_fresh(Time now) const noexcept {
    return has_status() && now - last_status_ <= protocol::smart_tool::kControllerLostAfter;
  }
  [[nodiscard]] bool running() const noexcept {
    return (status_.flags & protocol::smart_tool::status_flag::kRunning) != 0;
  }

  // --- result and program acknowledgement: the latest one not yet taken ---
  std::optional<protocol::smart_tool::RunResult> take_result() noexcept { return std::exchange(result_, {}); }
  std::optional<protocol::smart_tool::ProgramAck> take_ack() noexcept { return std::exchange(ack_, {}); }

  // --- the bus ---
  [[nodiscard]] bool bus_open() const noexcept { return bus_.is_open(); }
  // Bus-off, down, or the last send/receive failed; false while the bus is not open (see bus_open()).
  [[nodiscard]] bool bus_fault() const noexcept { return bus_.is_open() && bus_fault_; }
  // What is wrong with the bus ("" when nothing): why it is not open, or its fault.
  [[nodiscard]] std::string_view bus_problem() const noexcept {
    return bus_.is_open() ? bus_problem_.view() : bus_.error();
  }
  [[nodiscard]] const hal::CanConfig& can_config() const noexcept { return bus_.config(); }
  [[nodiscard]] const hal::SupervisedCanBus& bus() const noexcept { return bus_; }
  [[nodiscard]] std::uint8_t node_id() const noexcept { return node_id_; }

 private:
  void handle(const hal::CanFrame& frame, Time now) noexcept;
  void note_heartbeat(const protocol::smart_tool::Heartbeat& beat, Time now) noexcept;
  Status send(const hal::CanFrame& frame) noexcept;
  void note_failure(std::string_view what, ErrorCode code) noexcept;

  hal::SupervisedCanBus bus_;
  std::uint8_t node_id_;
  bool bus_fault_ = false;
  bool bus_state_off_ = false;  // the last status() said bus-off or down
  runtime::TextBuffer<191> bus_problem_;

  std::uint64_t heartbeats_ = 0;
  Time last_heartbeat_{};
  protocol::smart_tool::Heartbeat heartbeat_;
  std::uint32_t missed_heartbeats_ = 0;
  std::uint32_t reboots_ = 0;

  protocol::smart_tool::Status status_;
  std::uint64_t status_count_ = 0;
  Time last_status_{};
  std::optional<protocol::smart_tool::RunResult> result_;
  std::optional<protocol::smart_tool::ProgramAck> ack_;
};

}  // namespace hubrt::tool_ecu
